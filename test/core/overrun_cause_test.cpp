// Which overruns are the scan's and which the machine's (docs/scan-engine.md, "overruns with
// the thread off the CPU"): work of a given CPU time, started on time, misses the periods it
// runs past the first; a missed period it does not explain was lost off the CPU.
#include <gtest/gtest.h>
#include <time.h>

#include <condition_variable>
#include <mutex>
#include <thread>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"

using namespace plc_cell;

namespace {
constexpr uint64_t kMs = 1000000;

uint64_t thread_cpu_ns() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return uint64_t(ts.tv_sec) * 1000000000ull + uint64_t(ts.tv_nsec);
}

// In one chosen scan: sleeps (off the CPU) or computes (on it) for 3.5 periods.
class SlowScan : public ScanHook {
 public:
  enum class How { Sleep, Compute };
  explicit SlowScan(How how) : how_(how) {}
  void before_program(uint64_t) override {
    if (++scans_ != 5) return;
    if (how_ == How::Sleep) {
      std::this_thread::sleep_for(std::chrono::microseconds(3500));
      return;
    }
    const uint64_t until = thread_cpu_ns() + 3500000;
    while (thread_cpu_ns() < until) {
    }
  }
  int scans() const { return scans_; }

 private:
  How how_;
  int scans_ = 0;
};

// A real-time loop at 1 ms until the slow scan and three more have run (bounded wait).
ScanStats run_with(SlowScan::How how) {
  Plc plc;
  SlowScan hook(how);
  plc.locked([&](ScanEngine& e, Memory&) {
    e.add_hook(&hook);
    return 0;
  });
  plc.load_program_text("ORG M1925\nOUT Y0\nEND\n", "slow.il");
  EXPECT_TRUE(plc.set_mode(RunMode::Run));
  std::mutex mu;
  std::condition_variable cv;
  bool past = false;
  RealTimeLoop loop(plc, std::chrono::milliseconds(1));
  loop.set_after_scan([&] {
    const int n = plc.locked([&](ScanEngine&, Memory&) { return hook.scans(); });
    std::lock_guard<std::mutex> lk(mu);
    past = n >= 8;
    cv.notify_all();
  });
  loop.start();
  {
    std::unique_lock<std::mutex> lk(mu);
    EXPECT_TRUE(cv.wait_for(lk, std::chrono::seconds(20), [&] { return past; })) << "the loop never got there";
  }
  loop.stop();
  return plc.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(&hook);
    return e.stats();
  });
}
}  // namespace

TEST(OverrunCause, WorkExplainsThePeriodsItRunsPastTheFirst) {
  EXPECT_EQ(overruns_off_cpu(2, kMs / 3, kMs), 2u) << "a third of a period of work misses none";
  EXPECT_EQ(overruns_off_cpu(1, kMs, kMs), 1u) << "work ending on the deadline misses none";
  EXPECT_EQ(overruns_off_cpu(1, kMs + 1, kMs), 0u);
  EXPECT_EQ(overruns_off_cpu(3, 3 * kMs / 2, kMs), 2u) << "1.5 periods of work miss one";
  EXPECT_EQ(overruns_off_cpu(3, 3200000, kMs), 0u) << "3.2 periods of work miss three";
  EXPECT_EQ(overruns_off_cpu(3, 5 * kMs, kMs), 0u) << "never fewer than none";
  EXPECT_EQ(overruns_off_cpu(0, 5 * kMs, kMs), 0u);
  EXPECT_EQ(overruns_off_cpu(4, 5 * kMs, 0), 0u) << "no period, nothing to tell";
}

// A scan that sleeps 3.5 ms misses at least three periods, none of them its work's.
TEST(OverrunCause, ASleepingScanOverrunsOffTheCpu) {
  const ScanStats st = run_with(SlowScan::How::Sleep);
  EXPECT_GE(st.overruns, 3u);
  EXPECT_EQ(st.overruns_off_cpu, st.overruns);
}

// A scan that computes for 3.5 ms of its thread's CPU time misses three periods by its own
// work (more if the machine also preempted it; the other scans compute for microseconds).
TEST(OverrunCause, AComputingScanOverrunsByItsWork) {
  const ScanStats st = run_with(SlowScan::How::Compute);
  EXPECT_GE(st.overruns, 3u);
  EXPECT_EQ(st.overruns - st.overruns_off_cpu, 3u);
}
