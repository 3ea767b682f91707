// The process's shared scan threads (SharedScanThread::process): with more than one, each
// new PLC goes to the thread with the fewest, so that cells spread over the cores.
#include <gtest/gtest.h>

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
