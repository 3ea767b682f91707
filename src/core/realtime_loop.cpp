#include "plc_cell/core/realtime_loop.h"

#include <pthread.h>
#include <sys/prctl.h>
#include <time.h>

#include <cstring>

namespace plc_cell {

namespace {
uint64_t mono_ns() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}
void sleep_until_ns(uint64_t t) {
  timespec ts;
  ts.tv_sec = static_cast<time_t>(t / 1000000000ull);
  ts.tv_nsec = static_cast<long>(t % 1000000000ull);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}
}  // namespace

RealTimeLoop::RealTimeLoop(Plc& plc, std::chrono::nanoseconds period) : plc_(plc), period_(period) {}

RealTimeLoop::~RealTimeLoop() { stop(); }

void RealTimeLoop::start() {
  if (running_) return;
  running_ = true;
  thread_ = std::thread([this] { run(); });
}

void RealTimeLoop::stop() {
  running_ = false;
  if (thread_.joinable()) thread_.join();
}

void RealTimeLoop::run() {
  // The default 50 us timer slack would be a floor under every wake latency.
  prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  if (priority_ > 0) {
    sched_param sp{};
    sp.sched_priority = priority_;
    const int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &sp);
    if (rc != 0) priority_error_ = std::string("SCHED_FIFO refused: ") + std::strerror(rc);
  }
  const uint64_t period = static_cast<uint64_t>(period_.count());
  // Continue the engine's clock where it stopped, so timers do not jump.
  const uint64_t base_us = plc_.locked([](ScanEngine& e, Memory&) { return e.now_us(); });
  const uint64_t epoch = mono_ns();
  uint64_t next = epoch + period;
  while (running_) {
    sleep_until_ns(next);
    const uint64_t woke = mono_ns();
    const uint64_t latency = woke > next ? woke - next : 0;
    const uint64_t now_us = base_us + (woke - epoch) / 1000;
    uint64_t exec = 0, missed = 0;
    plc_.locked([&](ScanEngine& e, Memory&) {
      e.scan(now_us);
      exec = mono_ns() - woke;
      next += period;
      const uint64_t done = mono_ns();
      if (done > next) {
        missed = (done - next) / period + 1;
        next += missed * period;
      }
      e.report_cycle(exec, latency, missed);
    });
    if (record_) latencies_.push_back(latency);
    if (after_scan_) after_scan_();
  }
}

}  // namespace plc_cell
