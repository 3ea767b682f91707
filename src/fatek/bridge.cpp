#include "plc_cell/fatek/bridge.h"

#include <algorithm>

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/backoff.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace fatek {

namespace {

std::chrono::steady_clock::duration period_of(double rate_hz) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
}

// The next time a poll is due; after an overrun, one period from now rather than a burst
// of the polls that were missed.
void advance(std::chrono::steady_clock::time_point& due, std::chrono::steady_clock::duration period,
             std::chrono::steady_clock::time_point now) {
  due += period;
  if (due < now) due = now + period;
}

}  // namespace

Bridge::Bridge(BridgeConfig cfg, Sinks sinks) : cfg_(std::move(cfg)), sinks_(std::move(sinks)) {
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
  io_period_ = period_of(cfg_.io_rate_hz);
  for (const auto& rg : cfg_.groups) {
    Group g;
    g.items = rg.spans;
    g.plan = plan_poll(g.items);
    g.period = period_of(rg.rate_hz);
    groups_.push_back(std::move(g));
  }
}

Bridge::~Bridge() { stop(); }

void Bridge::start() {
  if (thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    stopping_ = false;
  }
  thread_ = std::thread([this] { run(); });
}

void Bridge::stop() {
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void Bridge::recover() {
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    client_->transport().close();
  }
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    status_.connected = false;
    status_.last_error.clear();
    recover_ = true;
  }
  cv_.notify_all();
}

LinkStatus Bridge::status() const {
  std::lock_guard<std::mutex> lk(state_mu_);
  return status_;
}

void Bridge::fail(const std::string& what) {
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    status_.last_error = what;
    ++status_.errors;
  }
  if (sinks_.error) sinks_.error(what);
}

// Called with link_mu_ held: the link broke, the next turn reconnects.
void Bridge::drop_link() {
  client_->transport().close();
  std::lock_guard<std::mutex> lk(state_mu_);
  status_.connected = false;
}

// Called with link_mu_ held. An open transport is not proof of a PLC (a TCP gateway
// accepts with nothing behind it, a serial port opens with no cable), so a new link
// counts only once a slave has answered a loop-back at this station.
bool Bridge::connect_locked() {
  if (client_->transport().is_open()) return true;
  try {
    client_->transport().open();
    client_->loopback("PLC");
    std::lock_guard<std::mutex> lk(state_mu_);
    status_.connected = true;
    ++status_.reconnects;
    return true;
  } catch (const std::exception& e) {
    drop_link();
    fail(std::string("connect: ") + e.what());
    return false;
  }
}

template <typename F>
auto Bridge::transaction(F&& f) -> decltype(f()) {
  std::lock_guard<std::mutex> lk(link_mu_);
  // Worth a connection attempt now, whatever the back-off: someone is waiting for it.
  if (!connect_locked()) throw CommError(link_name_ + " is not connected: " + status().last_error);
  try {
    return f();
  } catch (const CommError& e) {
    fail(e.what());
    drop_link();
    throw;
  }
}

// One poll's transactions. A communication error drops the link (false); an error code
// from the PLC (a group beyond this PLC's memory, say) fails this poll only.
template <typename F>
bool Bridge::polled(std::string* error, F&& body) {
  try {
    body();
    return true;
  } catch (const CommError& e) {
    *error = e.what();
    fail(*error);
    drop_link();
    return false;
  } catch (const std::exception& e) {
    *error = e.what();
    fail(*error);
    return true;
  }
}

// Returns false when the link broke.
bool Bridge::poll_io() {
  IoResult r;
  bool up = true;
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    // Dropped meanwhile (recover()): the transport would reopen by itself, unconfirmed.
    if (!client_->transport().is_open()) return false;
    up = polled(&r.error, [&] {
      const auto t0 = Clock::now();
      const PlcStatus st = client_->status();
      const std::vector<std::vector<uint32_t>> v = run_poll(*client_, io_items_, io_plan_);
      const double ms = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
      {
        std::lock_guard<std::mutex> sl(state_mu_);
        status_.latency_last_ms = ms;
        status_.latency_max_ms = std::max(status_.latency_max_ms, ms);
        ++status_.polls;
      }
      r.ok = true;
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
  if (sinks_.io) sinks_.io(r);
  return up;
}

bool Bridge::poll_group(size_t g) {
  GroupResult r;
  r.group = g;
  bool up = true;
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    if (!client_->transport().is_open()) return false;
    up = polled(&r.error, [&] {
      for (const auto& item : run_poll(*client_, groups_[g].items, groups_[g].plan))
        r.values.insert(r.values.end(), item.begin(), item.end());
      r.ok = true;
    });
  }
  if (sinks_.group) sinks_.group(r);
  return up;
}

void Bridge::run() {
  Backoff backoff(cfg_.backoff_min_s, cfg_.backoff_max_s);
  io_due_ = Clock::now();
  for (auto& g : groups_) g.due = io_due_;
  for (;;) {
    {
      std::lock_guard<std::mutex> lk(state_mu_);
      if (stopping_) return;
      if (recover_) {
        recover_ = false;
        backoff.reset();
      }
    }
    bool up;
    {
      std::lock_guard<std::mutex> lk(link_mu_);
      up = connect_locked();
    }
    if (!up) {
      std::unique_lock<std::mutex> lk(state_mu_);
      cv_.wait_for(lk, std::chrono::duration<double>(backoff.failed()), [this] { return stopping_ || recover_; });
      continue;
    }
    backoff.reset();
    const auto now = Clock::now();
    if (now >= io_due_) {
      up = poll_io();
      advance(io_due_, io_period_, now);
    }
    for (size_t g = 0; g < groups_.size() && up; ++g) {  // a broken link ends the round
      if (Clock::now() < groups_[g].due) continue;
      up = poll_group(g);
      advance(groups_[g].due, groups_[g].period, now);
    }
    Clock::time_point next = io_due_;
    for (const auto& g : groups_) next = std::min(next, g.due);
    std::unique_lock<std::mutex> lk(state_mu_);
    cv_.wait_until(lk, next, [this] { return stopping_ || recover_; });
  }
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

void Bridge::set_run(bool run) {
  transaction([&] { client_->set_run(run); });
}

}  // namespace fatek
}  // namespace plc_cell
