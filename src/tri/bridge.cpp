#include "plc_cell/tri/bridge.h"

#include <chrono>

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace tri {

Bridge::Bridge(BridgeConfig cfg, Sinks sinks)
    : PolledLink(cfg.backoff_min_s, cfg.backoff_max_s, sinks.error), cfg_(std::move(cfg)), sinks_(std::move(sinks)) {
  check_link_settings(cfg_);
  ClientOptions co;
  co.id = cfg_.id;
  co.timeout_ms = int(cfg_.timeout_s * 1000);
  co.retries = cfg_.retries;
  std::unique_ptr<Transport> t = cfg_.tcp.empty()
                                     ? serial_transport(parse_serial_settings(cfg_.serial, "8N1", kDefaultBaud))
                                     : tcp_transport(cfg_.tcp);
  char id[8];
  std::snprintf(id, sizeof id, "%02X", unsigned(cfg_.id));
  link_name_ = t->describe() + " ID " + id;
  client_ = std::make_unique<Client>(std::move(t), co);

  // INPUT[1..] and OUTPUT[1..], 16 points a frame; the signals join them (or their own word).
  io_items_.push_back({parse_address("WX0"), cfg_.inputs / 16});
  io_items_.push_back({parse_address("WY0"), cfg_.outputs / 16});
  for (const auto& s : cfg_.signals) io_items_.push_back({s.second, 1});
  io_plan_ = plan_poll(io_items_);
  add_poll(cfg_.io_rate_hz, [this] { return poll_io(); });
  for (const auto& rg : cfg_.groups) {
    groups_.push_back(plan_poll(rg.spans));
    const size_t k = groups_.size() - 1;
    add_poll(rg.rate_hz, [this, k] { return poll_group(k); });
  }
}

Bridge::~Bridge() { stop(); }

// Only the PLC with this ID answers IR (and with its ID).
void Bridge::confirm() {
  Request r;
  r.cmd = Cmd::ReadId;
  client_->transact(r);
}

uint64_t Bridge::frames_sent() {
  std::lock_guard<std::mutex> lk(link_mu_);
  return client_->requests();
}

bool Bridge::poll_io() {
  IoResult r;
  return poll_into(r, sinks_.io, [&] {
    const auto t0 = std::chrono::steady_clock::now();
    for (const auto& f : forced()) {  // held: written again before each image is read
      Request w;
      w.cmd = Cmd::ForceBit;
      w.a = wb_address(f.first);
      w.values = {f.second ? 1u : 0u};
      client_->transact(w);
    }
    const std::vector<std::vector<uint32_t>> v = run_poll(*client_, io_plan_);
    count_poll(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    r.run = !halted_;
    r.x.assign(256, false);
    r.y.assign(256, false);
    for (uint32_t i = 0; i < cfg_.inputs; ++i) r.x[i] = (v[0][i / 16] >> (i % 16)) & 1;
    for (uint32_t i = 0; i < cfg_.outputs; ++i) r.y[i] = (v[1][i / 16] >> (i % 16)) & 1;
    for (size_t i = 0; i < cfg_.signals.size(); ++i) r.signals.push_back(v[2 + i][0] != 0);
  });
}

bool Bridge::poll_group(size_t g) {
  GroupResult r;
  r.group = g;
  return poll_into(r, sinks_.group, [&] {
    for (const auto& item : run_poll(*client_, groups_[g])) r.values.insert(r.values.end(), item.begin(), item.end());
  });
}

Address Bridge::resolve(const std::string& text) const {
  for (const auto& s : cfg_.signals)
    if (s.first == text) return s.second;
  return parse_point(text);
}

std::vector<uint32_t> Bridge::read(const Address& start, uint32_t count) {
  const PollPlan plan = plan_poll({PollItem{start, count}});  // before the link: a bad request costs no frame
  return transaction([&] { return run_poll(*client_, plan).at(0); });
}

void Bridge::write(const Address& start, const std::vector<uint32_t>& raw) {
  const std::vector<Request> frames = plan_write(start, raw);
  transaction([&] {
    for (const Request& r : frames) client_->transact(r);
  });
}

void Bridge::force(const Address& bit, bool value) {
  const uint32_t wb = wb_address(bit);
  transaction([&] {
    Request w;
    w.cmd = Cmd::ForceBit;
    w.a = wb;
    w.values = {value ? 1u : 0u};
    client_->transact(w);
  });
  std::lock_guard<std::mutex> lk(forced_mu_);
  forced_[wb] = {bit, value};
}

std::vector<Address> Bridge::release(const Address* bit) {
  std::lock_guard<std::mutex> lk(forced_mu_);
  std::vector<Address> freed;
  if (bit) {
    const auto it = forced_.find(wb_address(*bit));
    if (it != forced_.end()) {
      freed.push_back(it->second.first);
      forced_.erase(it);
    }
  } else {
    for (const auto& f : forced_) freed.push_back(f.second.first);
    forced_.clear();
  }
  return freed;
}

std::vector<std::pair<Address, bool>> Bridge::forced() const {
  std::lock_guard<std::mutex> lk(forced_mu_);
  std::vector<std::pair<Address, bool>> out;
  for (const auto& f : forced_) out.push_back(f.second);
  return out;
}

void Bridge::set_run(bool run) {
  transaction([&] {
    Request r;
    r.cmd = run ? Cmd::Resume : Cmd::Halt;
    client_->transact(r);
    halted_ = !run;
  });
}

}  // namespace tri
}  // namespace plc_cell
