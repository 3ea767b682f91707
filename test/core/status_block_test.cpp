// A subsystem's status block as it last wrote it (core/status_block.h): it holds until
// anything in its registers or relays changes, a relay's DISABLE flag included.
#include <gtest/gtest.h>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/status_block.h"

namespace plc_cell {
namespace {

TEST(StatusBlock, HoldsWhatWasTakenUntilAWordOrARelayOfItChanges) {
  Memory m;
  StatusBlock<3, 2> block(Area::R, 4072, Area::M, 1992);
  EXPECT_FALSE(block.holds(m));  // nothing taken yet
  m.set_reg(Area::R, 4073, 7);
  m.set_bit(Area::M, 1993, true);
  block.take(m);
  EXPECT_TRUE(block.holds(m));
  m.set_reg(Area::R, 4071, 1);  // outside the block
  m.set_reg(Area::R, 4075, 1);
  m.set_bit(Area::M, 1991, true);
  m.set_bit(Area::M, 1994, true);
  EXPECT_TRUE(block.holds(m));
  m.set_reg(Area::R, 4074, 9);  // the last word
  EXPECT_FALSE(block.holds(m));
  block.take(m);
  m.set_bit(Area::M, 1992, true);  // the first relay
  EXPECT_FALSE(block.holds(m));
  m.set_bit(Area::M, 1992, false);
  EXPECT_TRUE(block.holds(m));
  m.set_disabled(Area::M, 1993, true);  // forced: same state, another byte
  EXPECT_FALSE(block.holds(m));
  block.take(m);
  EXPECT_TRUE(block.holds(m));
  block.forget();
  EXPECT_FALSE(block.holds(m));
}

}  // namespace
}  // namespace plc_cell
