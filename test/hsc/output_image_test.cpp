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

using Changes = std::vector<std::tuple<uint64_t, uint32_t, bool>>;

// An output image over a fresh memory, recording what reaches the terminal.
struct Terminal {
  Memory mem;
  OutputImage img{mem};
  Changes changes;
  Terminal() {
    img.observe([this](uint64_t t, uint32_t y, bool v) { changes.push_back({t, y, v}); });
  }
};

TEST(OutputImage, ReportsEachChangeOnceInOutputOrder) {
  Terminal term;
  Memory& mem = term.mem;
  OutputImage& img = term.img;
  Changes& seen = term.changes;
  for (uint32_t y : {0u, 7u, 8u, 63u, 200u, 255u}) mem.set_bit(Area::Y, y, true);
  img.refresh(0, 256, 10);
  img.refresh(0, 256, 20);  // nothing changed since
  mem.set_bit(Area::Y, 8, false);
  img.refresh(0, 256, 30);
  const Changes want = {
      {10, 0, true}, {10, 7, true}, {10, 8, true}, {10, 63, true}, {10, 200, true}, {10, 255, true}, {30, 8, false}};
  EXPECT_EQ(seen, want);
}

TEST(OutputImage, OwnedOutputsNeverReachTheTerminal) {
  Terminal term;
  Memory& mem = term.mem;
  OutputImage& img = term.img;
  Changes& seen = term.changes;
  img.own(0, true);
  img.own(1, true);
  mem.set_bit(Area::Y, 0, true);
  mem.set_bit(Area::Y, 1, true);
  mem.set_bit(Area::Y, 2, true);
  img.refresh(0, 256, 5);
  img.own(1, false);  // given back: the image reaches it at the next refresh
  img.refresh(0, 256, 6);
  const Changes want = {{5, 2, true}, {6, 1, true}};
  EXPECT_EQ(seen, want);
}

TEST(OutputImage, ImmediateRefreshOfAnUnalignedRangeTouchesOnlyThatRange) {
  Terminal term;
  Memory& mem = term.mem;
  OutputImage& img = term.img;
  Changes& seen = term.changes;
  for (uint32_t y = 0; y < 24; ++y) mem.set_bit(Area::Y, y, true);
  img.refresh(3, 10, 1);   // Y3-Y12: across a block boundary
  img.refresh(250, 20, 2); // past Y255: the rest is ignored
  ASSERT_EQ(seen.size(), 10u);
  EXPECT_EQ(std::get<1>(seen.front()), 3u);
  EXPECT_EQ(std::get<1>(seen.back()), 12u);
  seen.clear();
  img.refresh(0, 256, 3);  // the outputs the ranges left out
  ASSERT_EQ(seen.size(), 14u);
  EXPECT_EQ(std::get<1>(seen[2]), 2u);
  EXPECT_EQ(std::get<1>(seen[3]), 13u);
}

// A scan's refresh usually finds the whole image unchanged and stops there: a change in
// the last block, beside an owned output that changed too, must still be found.
TEST(OutputImage, AChangeInTheLastBlockIsFoundBesideAnOwnedOne) {
  Terminal term;
  Memory& mem = term.mem;
  OutputImage& img = term.img;
  img.own(254, true);
  img.refresh(0, 256, 1);
  mem.set_bit(Area::Y, 254, true);  // owned: never reaches the terminal
  img.refresh(0, 256, 2);
  EXPECT_TRUE(term.changes.empty());
  mem.set_bit(Area::Y, 255, true);
  img.refresh(0, 256, 3);
  EXPECT_EQ(term.changes, (Changes{{3, 255, true}}));
}

TEST(OutputImage, AForcedOutputShowsItsForcedLevel) {
  Terminal term;
  Memory& mem = term.mem;
  OutputImage& img = term.img;
  Changes& seen = term.changes;
  mem.set_disabled(Area::Y, 9, true);
  mem.force_bit(Area::Y, 9, true);  // state ON with the DISABLE flag beside it
  mem.set_bit(Area::Y, 9, false);   // the program cannot change it
  img.refresh(0, 256, 4);
  const Changes want = {{4, 9, true}};
  EXPECT_EQ(seen, want);
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
