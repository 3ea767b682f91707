// The process's shared scan threads (SharedScanThread::process): with more than one, each
// new PLC goes to the thread with the fewest, so that cells spread over the cores; a thread
// runs at the highest real-time priority its cells ask for.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"

using namespace plc_cell;

TEST(SharedScanThreads, EachNewPlcGoesToTheThreadWithTheFewest) {
  Plc a, b, c;
  const auto period = std::chrono::milliseconds(1);
  SharedScanThread& first = SharedScanThread::process(2);
  const size_t before = first.scanned_plcs();
  const uint64_t ia = first.add(a, period, nullptr);
  SharedScanThread& second = SharedScanThread::process(2);
  EXPECT_NE(&first, &second) << "the second PLC goes to the idle thread";
  const uint64_t ib = second.add(b, period, nullptr);
  EXPECT_EQ(&SharedScanThread::process(1), &first) << "one thread: always the first";
  SharedScanThread& third = SharedScanThread::process(2);
  EXPECT_EQ(&third, &first) << "a tie goes to the first";
  const uint64_t ic = third.add(c, period, nullptr);
  EXPECT_EQ(first.scanned_plcs(), before + 2);
  EXPECT_EQ(second.scanned_plcs(), 1u);
  first.remove(ia);
  second.remove(ib);
  first.remove(ic);
  EXPECT_EQ(first.scanned_plcs(), before);
  EXPECT_EQ(second.scanned_plcs(), 0u);
}

// A cell's rt_priority reaches the shared thread that scans it, as it reaches a cell's own
// loop: SCHED_FIFO at the highest priority of the thread's PLCs, never lowered by a PLC that
// asks for less; where the system refuses it, the thread keeps the normal scheduler and says why.
TEST(SharedScanThreads, RunAtTheHighestPriorityTheirPlcsAskFor) {
  Plc high, low;
  std::mutex mu;
  std::condition_variable cv;
  int policy = -1, prio = -1;
  auto observe = [&] {  // on the scan thread itself, after the PLC's scan
    sched_param sp{};
    int pol = 0;
    pthread_getschedparam(pthread_self(), &pol, &sp);
    std::lock_guard<std::mutex> lk(mu);
    policy = pol;
    prio = sp.sched_priority;
    cv.notify_all();
  };
  SharedScanThread& t = SharedScanThread::process(1);
  const uint64_t ih = t.add(high, std::chrono::milliseconds(1), observe, 7);
  const uint64_t il = t.add(low, std::chrono::milliseconds(1), nullptr, 3);
  bool scanned = false;
  {
    std::unique_lock<std::mutex> lk(mu);
    policy = -1;  // a scan after both were added
    scanned = cv.wait_for(lk, std::chrono::seconds(10), [&] { return policy != -1; });
  }
  const std::string refused = t.priority_error();
  t.remove(ih);  // before any return: the thread must not call observe once this test ends
  t.remove(il);
  ASSERT_TRUE(scanned) << "never scanned";
  if (refused.empty()) {
    EXPECT_EQ(t.priority(), 7);
    EXPECT_EQ(policy, SCHED_FIFO);
    EXPECT_EQ(prio, 7) << "the highest priority asked for, not the last";
  } else {
    EXPECT_NE(refused.find("SCHED_FIFO refused: "), std::string::npos) << refused;
    EXPECT_EQ(t.priority(), 0);
    EXPECT_EQ(policy, SCHED_OTHER);
  }
}

// Deadlines on one grid: the first grid point of the period after the moment of adding.
TEST(SharedScanThreads, TheFirstDeadlineIsTheNextPointOfTheGrid) {
  EXPECT_EQ(next_on_grid(1000, 1000, 1000), 2000u) << "added on a grid point: the next one";
  EXPECT_EQ(next_on_grid(1000, 1001, 1000), 2000u);
  EXPECT_EQ(next_on_grid(1000, 1999, 1000), 2000u);
  EXPECT_EQ(next_on_grid(1000, 2000, 1000), 3000u);
  EXPECT_EQ(next_on_grid(1000, 5500, 1000), 6000u);
  EXPECT_EQ(next_on_grid(1000, 5500, 10000), 11000u) << "a longer period has its own points";
  EXPECT_EQ(next_on_grid(1000, 400, 1000), 1000u) << "before the grid: its start";
  EXPECT_EQ(next_on_grid(1000, 5500, 0), 5500u) << "no period: now";
}

// PLCs of one period added at different moments are scanned at the same instants: the
// thread wakes once per period for all of them, not once per PLC (which 100 nodelets
// loaded one by one cost before: their phases were the moments they were added).
TEST(SharedScanThreads, PlcsOfOnePeriodAddedApartShareEachWakeUp) {
  constexpr int kPlcs = 6;
  Plc plcs[kPlcs];
  std::mutex mu;
  std::condition_variable cv;
  int first_scans = 0;
  SharedScanThread t;  // after plcs: stopped before they go
  const auto period = std::chrono::milliseconds(1);
  const uint64_t first = t.add(plcs[0], period, [&] {
    std::lock_guard<std::mutex> lk(mu);
    ++first_scans;
    cv.notify_all();
  });
  for (int i = 1; i < kPlcs; ++i) {
    // A phase apart from the others' (much longer than a scan): the stimulus, not a wait.
    const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(150);
    while (std::chrono::steady_clock::now() < until) {
    }
    t.add(plcs[i], period, nullptr);
  }
  // Every PLC's scan count at one instant: with all their locks held the thread scans none,
  // so the counts are of whole wake-ups but for the one it may be in the middle of.
  const auto snapshot = [&plcs](uint64_t* out) {
    std::function<void(int)> hold = [&](int i) {
      if (i == kPlcs) return;
      plcs[i].locked([&](ScanEngine& e, Memory&) {
        out[i] = e.stats().scans;
        hold(i + 1);
      });
    };
    hold(0);
  };
  uint64_t before[kPlcs], after[kPlcs];
  snapshot(before);
  const uint64_t wakeups0 = t.wakeups();
  bool enough;
  {
    std::unique_lock<std::mutex> lk(mu);
    const int target = first_scans + 30;
    enough = cv.wait_for(lk, std::chrono::seconds(20), [&] { return first_scans >= target; });
  }
  snapshot(after);
  const uint64_t wakeups = t.wakeups() - wakeups0, scanned = after[0] - before[0];
  t.remove(first);  // first_scans' owner goes at the end of this test
  ASSERT_TRUE(enough) << "the first PLC was not scanned 30 times";
  EXPECT_LE(wakeups, scanned + 2) << "a wake-up per PLC and period, not one per period";
  // Each wake-up scans them all: over the same window every PLC was scanned as often as the
  // first, but for a wake-up a snapshot fell in the middle of (at each end).
  for (int i = 1; i < kPlcs; ++i) {
    const int64_t d = int64_t(after[i] - before[i]) - int64_t(scanned);
    EXPECT_LE(std::abs(d), 2) << "PLC " << i << ": " << after[i] - before[i] << " scans, the first " << scanned;
  }
}

// A PLC's first scan costs several later ones: of PLCs added at once, at most a few make it
// at one wake-up; the rest wait for the next grid points.
TEST(SharedScanThreads, AtMostAFewFirstScansShareAWakeUp) {
  EXPECT_EQ(first_scan_point({}, 5000, 1000, 2), 5000u);
  EXPECT_EQ(first_scan_point({5000}, 5000, 1000, 2), 5000u);
  EXPECT_EQ(first_scan_point({5000, 5000}, 5000, 1000, 2), 6000u) << "the first point is full";
  EXPECT_EQ(first_scan_point({5000, 5000, 6000, 6000, 7000}, 5000, 1000, 2), 7000u);
  EXPECT_EQ(first_scan_point({5000, 5000, 7000, 7000}, 5000, 1000, 2), 6000u) << "a free point between full ones";
  EXPECT_EQ(first_scan_point({4000, 4000, 4000}, 5000, 1000, 2), 5000u) << "points before next do not count";
  EXPECT_EQ(first_scan_point({5000}, 5000, 1000, 0), 6000u) << "a budget of none is one";
}

TEST(SharedScanThreads, PlcsAddedAtOnceMakeTheirFirstScansAFewAtAWakeUp) {
  // 70 PLCs of a 400 ms period added at once: their first scans come at three wake-ups 400 ms
  // apart, 32, 32 and 6 (kFirstScansPerWake), each wake-up's in a burst.
  constexpr size_t kPlcs = 70;
  static_assert(SharedScanThread::kFirstScansPerWake == 32, "the groups below");
  std::vector<Plc> plcs(kPlcs);
  std::mutex mu;
  std::condition_variable cv;
  std::vector<std::chrono::steady_clock::time_point> firsts;
  std::vector<bool> seen(kPlcs, false);
  SharedScanThread t;  // after plcs: stopped before they go
  std::vector<uint64_t> ids;
  for (size_t i = 0; i < kPlcs; ++i)
    ids.push_back(t.add(plcs[i], std::chrono::milliseconds(400), [&, i] {
      std::lock_guard<std::mutex> lk(mu);
      if (seen[i]) return;
      seen[i] = true;
      firsts.push_back(std::chrono::steady_clock::now());
      cv.notify_all();
    }));
  bool all;
  {
    std::unique_lock<std::mutex> lk(mu);
    all = cv.wait_for(lk, std::chrono::seconds(20), [&] { return firsts.size() == kPlcs; });
  }
  for (uint64_t id : ids) t.remove(id);
  ASSERT_TRUE(all) << "only " << firsts.size() << " of " << kPlcs << " PLCs scanned within 20 s";
  // Bursts: first scans less than 200 ms apart belong to one wake-up (the next is 400 ms on).
  std::vector<size_t> bursts{1};
  for (size_t k = 1; k < firsts.size(); ++k) {
    if (firsts[k] - firsts[k - 1] > std::chrono::milliseconds(200)) bursts.push_back(0);
    ++bursts.back();
  }
  EXPECT_EQ(bursts, (std::vector<size_t>{32, 32, 6}));
}
