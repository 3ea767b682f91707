// The physical outputs (docs/counters-and-interrupts.md "Outputs"): the I/O refresh reports
// every change of the Y image once, in output order, with its instant; an output owned by a
// pulse generator never reaches the terminal; FUN74 IMDIO refreshes any range, aligned to the
// eight-output blocks the comparison works in or not; forced outputs show their forced level.
#include <gtest/gtest.h>

#include <tuple>
#include <vector>

#include "plc_cell/core/memory.h"
#include "plc_cell/hsc/output_image.h"

namespace plc_cell {
namespace hsc {
namespace {

struct Seen {
  std::vector<std::tuple<uint64_t, uint32_t, bool>> changes;
};

TEST(OutputImage, ReportsEachChangeOnceInOutputOrder) {
  Memory mem;
  OutputImage img(mem);
  Seen s;
  img.observe([&](uint64_t t, uint32_t y, bool v) { s.changes.push_back({t, y, v}); });
  for (uint32_t y : {0u, 7u, 8u, 63u, 200u, 255u}) mem.set_bit(Area::Y, y, true);
  img.refresh(0, 256, 10);
  img.refresh(0, 256, 20);  // nothing changed since
  mem.set_bit(Area::Y, 8, false);
  img.refresh(0, 256, 30);
  const std::vector<std::tuple<uint64_t, uint32_t, bool>> want = {
      {10, 0, true}, {10, 7, true}, {10, 8, true}, {10, 63, true}, {10, 200, true}, {10, 255, true}, {30, 8, false}};
  EXPECT_EQ(s.changes, want);
}

TEST(OutputImage, OwnedOutputsNeverReachTheTerminal) {
  Memory mem;
  OutputImage img(mem);
  Seen s;
  img.observe([&](uint64_t t, uint32_t y, bool v) { s.changes.push_back({t, y, v}); });
  img.own(0, true);
  img.own(1, true);
  mem.set_bit(Area::Y, 0, true);
  mem.set_bit(Area::Y, 1, true);
  mem.set_bit(Area::Y, 2, true);
  img.refresh(0, 256, 5);
  img.own(1, false);  // given back: the image reaches it at the next refresh
  img.refresh(0, 256, 6);
  const std::vector<std::tuple<uint64_t, uint32_t, bool>> want = {{5, 2, true}, {6, 1, true}};
  EXPECT_EQ(s.changes, want);
}

TEST(OutputImage, ImmediateRefreshOfAnUnalignedRangeTouchesOnlyThatRange) {
  Memory mem;
  OutputImage img(mem);
  Seen s;
  img.observe([&](uint64_t t, uint32_t y, bool v) { s.changes.push_back({t, y, v}); });
  for (uint32_t y = 0; y < 24; ++y) mem.set_bit(Area::Y, y, true);
  img.refresh(3, 10, 1);   // Y3-Y12: across a block boundary
  img.refresh(250, 20, 2); // past Y255: the rest is ignored
  ASSERT_EQ(s.changes.size(), 10u);
  EXPECT_EQ(std::get<1>(s.changes.front()), 3u);
  EXPECT_EQ(std::get<1>(s.changes.back()), 12u);
  s.changes.clear();
  img.refresh(0, 256, 3);  // the outputs the ranges left out
  ASSERT_EQ(s.changes.size(), 14u);
  EXPECT_EQ(std::get<1>(s.changes[2]), 2u);
  EXPECT_EQ(std::get<1>(s.changes[3]), 13u);
}

TEST(OutputImage, AForcedOutputShowsItsForcedLevel) {
  Memory mem;
  OutputImage img(mem);
  Seen s;
  img.observe([&](uint64_t t, uint32_t y, bool v) { s.changes.push_back({t, y, v}); });
  mem.set_disabled(Area::Y, 9, true);
  mem.force_bit(Area::Y, 9, true);  // state ON with the DISABLE flag beside it
  mem.set_bit(Area::Y, 9, false);   // the program cannot change it
  img.refresh(0, 256, 4);
  const std::vector<std::tuple<uint64_t, uint32_t, bool>> want = {{4, 9, true}};
  EXPECT_EQ(s.changes, want);
}

TEST(OutputImage, AFollowingSourceRunsWhileItsOutputIsOn) {
  Memory mem;
  OutputImage img(mem);
  PulseSource enc("enc", 0, 1);
  img.follow(4, &enc, 1000);
  mem.set_bit(Area::Y, 4, true);
  img.refresh(0, 256, 1000000);
  EXPECT_EQ(enc.rate_hz(), 1000);
  mem.set_bit(Area::Y, 4, false);
  img.refresh(0, 256, 2000000);
  EXPECT_EQ(enc.rate_hz(), 0);
  EXPECT_EQ(enc.quarter(2000000), 4);  // one period at 1 kHz: four quarters
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
