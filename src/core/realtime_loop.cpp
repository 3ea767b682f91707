#include "plc_cell/core/realtime_loop.h"

#include <pthread.h>
#include <sys/prctl.h>
#include <time.h>

#include <algorithm>
#include <array>
#include <cstring>

namespace plc_cell {

namespace {
uint64_t mono_ns() {
  timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}
uint64_t thread_cpu_ns() {  // a system call: once per wake-up, and after a scan that overran
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}
void sleep_until_ns(uint64_t t) {
  timespec ts;
  ts.tv_sec = static_cast<time_t>(t / 1000000000ull);
  ts.tv_nsec = static_cast<long>(t % 1000000000ull);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) != 0) {
  }
}

// One scan started at woke (the monotonic clock) at the engine time of woke, due at *next:
// accounted, *next moved past it (periods missed skipped, not caught up); cpu_woke is the
// thread's CPU time when it woke for this scan (or for the round of scans it is one of).
// Returns the wake latency. One clock read per scan: with 100 cells on a shared thread in a
// virtual machine, four reads per scan were a fifth of the thread's time (perf).
uint64_t scan_once(Plc& plc, uint64_t woke, uint64_t base_us, uint64_t epoch, uint64_t period, uint64_t* next,
                   uint64_t cpu_woke) {
  const uint64_t latency = woke > *next ? woke - *next : 0;
  const uint64_t now_us = base_us + (woke - epoch) / 1000;
  plc.locked([&](ScanEngine& e, Memory&) {
    e.scan(now_us);
    const uint64_t done = mono_ns();
    const uint64_t exec = done - woke;
    *next += period;
    uint64_t missed = 0, off_cpu = 0;
    if (done > *next) {
      missed = (done - *next) / period + 1;
      *next += missed * period;
      off_cpu = overruns_off_cpu(missed, thread_cpu_ns() - cpu_woke, period);
    }
    e.report_cycle(exec, latency, missed, off_cpu);
  });
  return latency;
}
}  // namespace

uint64_t overruns_off_cpu(uint64_t missed, uint64_t on_cpu_ns, uint64_t period_ns) {
  if (period_ns == 0) return 0;
  const uint64_t by_work = on_cpu_ns > period_ns ? (on_cpu_ns - period_ns) / period_ns + 1 : 0;
  return missed - std::min(missed, by_work);
}

uint64_t next_on_grid(uint64_t grid_ns, uint64_t now_ns, uint64_t period_ns) {
  if (period_ns == 0) return now_ns;
  if (now_ns < grid_ns) return grid_ns;
  return grid_ns + ((now_ns - grid_ns) / period_ns + 1) * period_ns;
}

uint64_t first_scan_point(const std::vector<uint64_t>& firsts, uint64_t next_ns, uint64_t period_ns, size_t per_wake) {
  for (uint64_t at = next_ns;; at += std::max<uint64_t>(period_ns, 1))
    if (size_t(std::count(firsts.begin(), firsts.end(), at)) < std::max<size_t>(per_wake, 1)) return at;
}

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
    const uint64_t latency = scan_once(plc_, mono_ns(), base_us, epoch, period, &next, thread_cpu_ns());
    if (record_) latencies_.push_back(latency);
    if (after_scan_) after_scan_();
  }
}

SharedScanThread& SharedScanThread::process(unsigned threads) {
  static std::array<SharedScanThread, kMaxThreads> pool;
  static std::mutex pick_mu;  // two cells added at once do not both pick the same thread
  std::lock_guard<std::mutex> lk(pick_mu);
  SharedScanThread* best = &pool[0];
  for (unsigned i = 1; i < std::min(threads, kMaxThreads); ++i)
    if (pool[i].scanned_plcs() < best->scanned_plcs()) best = &pool[i];
  return *best;
}

size_t SharedScanThread::scanned_plcs() {
  std::lock_guard<std::mutex> lk(mu_);
  return entries_.size();
}

SharedScanThread::~SharedScanThread() {
  {
    std::lock_guard<std::mutex> lk(mu_);
    stopping_ = true;
  }
  cv_.notify_all();
  if (thread_.joinable()) thread_.join();
}

int SharedScanThread::priority() {
  std::lock_guard<std::mutex> lk(mu_);
  return priority_;
}

std::string SharedScanThread::priority_error() {
  std::lock_guard<std::mutex> lk(mu_);
  return priority_error_;
}

uint64_t SharedScanThread::wakeups() {
  std::lock_guard<std::mutex> lk(mu_);
  return wakeups_;
}

uint64_t SharedScanThread::add(Plc& plc, std::chrono::nanoseconds period, std::function<void()> after_scan,
                               int priority) {
  const uint64_t base_us = plc.locked([](ScanEngine& e, Memory&) { return e.now_us(); });
  std::lock_guard<std::mutex> lk(mu_);
  const uint64_t p = std::max<uint64_t>(1, uint64_t(period.count())), now = mono_ns();
  if (grid_ns_ == 0) grid_ns_ = now;
  // Cells added a few milliseconds apart (nodelets loaded one by one) would otherwise each
  // have a phase of their own: 100 cells at 1 ms woke the thread 100 times a millisecond,
  // and the kernel's sleep and wake-up took more of it than the scans.
  std::vector<uint64_t> firsts;
  for (const Entry& e : entries_)
    if (!e.scanned) firsts.push_back(e.next_ns);
  const uint64_t next = first_scan_point(firsts, next_on_grid(grid_ns_, now, p), p, kFirstScansPerWake);
  entries_.push_back(Entry{next_id_, &plc, p, base_us, next - p, next, std::move(after_scan)});
  if (!thread_.joinable()) thread_ = std::thread([this] { run(); });
  if (priority > priority_) {
    sched_param sp{};
    sp.sched_priority = priority;
    const int rc = pthread_setschedparam(thread_.native_handle(), SCHED_FIFO, &sp);
    if (rc == 0) {
      priority_ = priority;
      priority_error_.clear();
    } else {
      priority_error_ = std::string("SCHED_FIFO refused: ") + std::strerror(rc);
    }
  }
  cv_.notify_all();
  return next_id_++;
}

void SharedScanThread::remove(uint64_t id) {
  std::lock_guard<std::mutex> lk(mu_);
  entries_.erase(std::remove_if(entries_.begin(), entries_.end(), [id](const Entry& e) { return e.id == id; }),
                 entries_.end());
}

void SharedScanThread::run() {
  prctl(PR_SET_TIMERSLACK, 1UL, 0, 0, 0);
  std::unique_lock<std::mutex> lk(mu_);
  while (!stopping_) {
    if (entries_.empty()) {
      cv_.wait(lk);
      continue;
    }
    uint64_t due = entries_.front().next_ns;
    for (const Entry& e : entries_) due = std::min(due, e.next_ns);
    lk.unlock();  // a cell added meanwhile waits at most this sleep
    sleep_until_ns(due);
    const uint64_t cpu_woke = thread_cpu_ns();
    lk.lock();
    ++wakeups_;
    uint64_t now = mono_ns();  // read again after each cell's after-scan, its time unknown
    for (Entry& e : entries_) {
      if (e.next_ns > now) continue;
      scan_once(*e.plc, now, e.base_us, e.epoch_ns, e.period_ns, &e.next_ns, cpu_woke);
      e.scanned = true;
      if (e.after_scan) e.after_scan();
      now = mono_ns();
    }
  }
}

}  // namespace plc_cell
