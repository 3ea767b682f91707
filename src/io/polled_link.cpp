#include "plc_cell/io/polled_link.h"

#include <algorithm>

#include "plc_cell/io/backoff.h"

namespace plc_cell {
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

PolledLink::PolledLink(double backoff_min_s, double backoff_max_s, std::function<void(const std::string&)> on_error)
    : backoff_min_s_(backoff_min_s), backoff_max_s_(backoff_max_s), on_error_(std::move(on_error)) {}

PolledLink::~PolledLink() { stop(); }

void PolledLink::add_poll(double rate_hz, std::function<bool()> body) {
  polls_.push_back(Poll{period_of(rate_hz), Clock::time_point{}, std::move(body)});
}

void PolledLink::start() {
  if (thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    stopping_ = false;
  }
  thread_ = std::thread([this] { run(); });
}

void PolledLink::stop() {
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void PolledLink::recover() {
  {
    std::lock_guard<std::mutex> lk(link_mu_);
    transport().close();
  }
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    status_.connected = false;
    status_.last_error.clear();
    recover_ = true;
  }
  cv_.notify_all();
}

LinkStatus PolledLink::status() const {
  std::lock_guard<std::mutex> lk(state_mu_);
  return status_;
}

void PolledLink::count_poll(double ms) {
  std::lock_guard<std::mutex> lk(state_mu_);
  status_.latency_last_ms = ms;
  status_.latency_max_ms = std::max(status_.latency_max_ms, ms);
  ++status_.polls;
}

void PolledLink::count_delivery(bool ok) {
  std::lock_guard<std::mutex> lk(state_mu_);
  if (ok) status_.failed_polls_in_row = 0, status_.delivered = true;
  else ++status_.failed_polls_in_row;
}

LinkHealth link_health(const LinkStatus& s) {
  if (!s.connected) return {LinkLevel::Error, "disconnected: " + s.last_error};
  const uint64_t n = s.failed_polls_in_row;
  if (n >= kLinkErrorPolls)
    return {LinkLevel::Error, "connected, but the last " + std::to_string(n) + " polls failed: " + s.last_error};
  if (n > 0) return {LinkLevel::Warn, "connected, the last poll failed: " + s.last_error};
  return {LinkLevel::Ok, "connected"};
}

void PolledLink::fail(const std::string& what) {
  {
    std::lock_guard<std::mutex> lk(state_mu_);
    status_.last_error = what;
    ++status_.errors;
  }
  if (on_error_) on_error_(what);
}

void PolledLink::drop_link() {
  transport().close();
  std::lock_guard<std::mutex> lk(state_mu_);
  status_.connected = false;
}

// Called with link_mu_ held.
bool PolledLink::connect_locked() {
  if (transport().is_open()) return true;
  try {
    transport().open();
    confirm();
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

void PolledLink::run() {
  Backoff backoff(backoff_min_s_, backoff_max_s_);
  const Clock::time_point t0 = Clock::now();
  for (auto& p : polls_) p.due = t0;
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
    for (size_t k = 0; k < polls_.size() && up; ++k) {  // a broken link ends the round
      if (Clock::now() < polls_[k].due) continue;
      up = polls_[k].body();
      advance(polls_[k].due, polls_[k].period, now);
    }
    Clock::time_point next = Clock::time_point::max();
    for (const auto& p : polls_) next = std::min(next, p.due);
    std::unique_lock<std::mutex> lk(state_mu_);
    if (next == Clock::time_point::max()) cv_.wait(lk, [this] { return stopping_ || recover_; });
    else cv_.wait_until(lk, next, [this] { return stopping_ || recover_; });
  }
}

}  // namespace plc_cell
