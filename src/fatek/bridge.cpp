#include "plc_cell/fatek/bridge.h"

#include <algorithm>
#include <chrono>

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace fatek {

Bridge::Bridge(BridgeConfig cfg, Sinks sinks)
    : PolledLink(cfg.backoff_min_s, cfg.backoff_max_s, sinks.error), cfg_(std::move(cfg)), sinks_(std::move(sinks)) {
  check_link_settings(cfg_);
  ClientOptions co;
  co.station = cfg_.station;
  co.timeout_ms = int(cfg_.timeout_s * 1000);
  co.retries = cfg_.retries;
  std::unique_ptr<Transport> t =
      cfg_.tcp.empty() ? serial_transport(parse_serial_settings(cfg_.serial)) : tcp_transport(cfg_.tcp);
  link_name_ = t->describe() + " station " + std::to_string(cfg_.station);
  client_ = std::make_unique<Client>(std::move(t), co);

  // WX0..WX240 and WY0..WY240 are one 48 frame of weight 32; the signals join it.
  io_items_.push_back({parse_address("WX0"), 16});
  io_items_.push_back({parse_address("WY0"), 16});
  for (const auto& s : cfg_.signals) io_items_.push_back({s.second, 1});
  io_plan_ = plan_poll(io_items_);
  add_poll(cfg_.io_rate_hz, [this] { return poll_io(); });
  for (const auto& rg : cfg_.groups) {
    Group g;
    g.items = rg.spans;
    g.plan = plan_poll(g.items);
    groups_.push_back(std::move(g));
    const size_t k = groups_.size() - 1;
    add_poll(rg.rate_hz, [this, k] { return poll_group(k); });
  }
}

Bridge::~Bridge() { stop(); }

// Returns false when the link broke.
bool Bridge::poll_io() {
  IoResult r;
  return poll_into(r, sinks_.io, [&] {
    const auto t0 = std::chrono::steady_clock::now();
    const PlcStatus st = client_->status();
    const std::vector<std::vector<uint32_t>> v = run_poll(*client_, io_items_, io_plan_);
    count_poll(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
    r.run = st.run;
    r.x.resize(256);
    r.y.resize(256);
    for (uint32_t i = 0; i < 256; ++i) {
      r.x[i] = (v[0][i / 16] >> (i % 16)) & 1;
      r.y[i] = (v[1][i / 16] >> (i % 16)) & 1;
    }
    for (size_t i = 0; i < cfg_.signals.size(); ++i) r.signals.push_back(v[2 + i][0] != 0);
  });
}

bool Bridge::poll_group(size_t g) {
  GroupResult r;
  r.group = g;
  return poll_into(r, sinks_.group, [&] {
    for (const auto& item : run_poll(*client_, groups_[g].items, groups_[g].plan))
      r.values.insert(r.values.end(), item.begin(), item.end());
  });
}

Address Bridge::resolve(const std::string& text) const {
  for (const auto& s : cfg_.signals)
    if (s.first == text) return s.second;
  return parse_address(text);
}

std::vector<uint32_t> Bridge::read(const Address& start, uint32_t count) {
  check_span(start, count);  // before the link: a bad request costs no transaction
  return transaction([&] { return client_->read(start, count); });
}

void Bridge::write(const Address& start, const std::vector<uint32_t>& raw) {
  check_span(start, uint32_t(raw.size()));
  transaction([&] { client_->write(start, raw); });
}

void Bridge::force(const Address& bit, bool value) {
  // Locked first and then set: the program cannot overwrite the new state in between.
  transaction([&] {
    client_->control(bit, Action::Disable);
    client_->control(bit, value ? Action::Set : Action::Reset);
  });
}

std::vector<Address> Bridge::release(const Address* bit) {
  std::vector<Address> spans;  // starts of the ranges to look at, with their sizes
  std::vector<uint32_t> sizes;
  if (bit) {
    spans.push_back(*bit);
    sizes.push_back(1);
  } else {
    for (int ai = 0; ai < kAreaCount; ++ai) {
      const Area area = static_cast<Area>(ai);
      if (!is_discrete(area)) continue;
      spans.push_back(Address{area, Width::Bit, 0});
      sizes.push_back(area_size(area));
    }
  }
  return transaction([&] {
    std::vector<Address> freed;
    for (size_t k = 0; k < spans.size(); ++k) {
      // Command 43 tells which points are locked, so only those get a 42 ENABLE and the
      // answer lists what was actually freed.
      const std::vector<bool> disabled = client_->read_disabled(spans[k], sizes[k]);
      for (uint32_t i = 0; i < disabled.size(); ++i) {
        if (!disabled[i]) continue;
        const Address p = offset_address(spans[k], i);
        client_->control(p, Action::Enable);
        freed.push_back(p);
      }
    }
    return freed;
  });
}

std::vector<bool> Bridge::forced(const std::vector<Address>& bits) {
  for (const Address& b : bits)
    if (b.width != Width::Bit || !is_discrete(b.area)) throw Error(format_address(b) + " is not a discrete");
  return transaction([&] {
    std::vector<bool> out(bits.size());
    for (size_t i = 0; i < bits.size();) {
      // bits[i..j) of one area, each the next of the one before
      size_t j = i + 1;
      while (j < bits.size() && bits[j].area == bits[i].area && bits[j].index == bits[j - 1].index + 1 &&
             j - i < kMaxDiscretes)
        ++j;
      const std::vector<bool> run = client_->read_disabled(bits[i], uint32_t(j - i));
      for (size_t k = i; k < j; ++k) out[k] = run[k - i];
      i = j;
    }
    return out;
  });
}

void Bridge::set_run(bool run) {
  transaction([&] { client_->set_run(run); });
}

}  // namespace fatek
}  // namespace plc_cell
