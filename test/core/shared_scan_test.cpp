// The process's shared scan threads (SharedScanThread::process): with more than one, each
// new PLC goes to the thread with the fewest, so that cells spread over the cores; a thread
// runs at the highest real-time priority its cells ask for.
#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <condition_variable>
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
