#include <gtest/gtest.h>

#include "plc_cell/core/address.h"
#include "plc_cell/core/memory.h"

using namespace plc_cell;

TEST(Memory, WordViewsPutTheLowestDiscreteInBitZero) {
  Memory m;
  m.set_bit(Area::Y, 8, true);
  m.set_bit(Area::Y, 23, true);
  EXPECT_EQ(m.read(parse_address("WY8")), 0x8001u);
  m.write(parse_address("WY8"), 0xAAAA);  // the manual's cmd-47 example
  EXPECT_FALSE(m.bit(Area::Y, 8));
  EXPECT_TRUE(m.bit(Area::Y, 9));
  EXPECT_TRUE(m.bit(Area::Y, 23));
}

TEST(Memory, DoubleWordsKeepTheLowWordAtTheLowerAddress) {
  Memory m;
  // DWM0 = 003547BAH means M31..M0 (spec 1.3): M1, M3, M4, M5, M7 ... are on.
  m.write(parse_address("DWM0"), 0x003547BA);
  EXPECT_EQ(m.read(parse_address("WM0")), 0x47BAu);
  EXPECT_EQ(m.read(parse_address("WM16")), 0x0035u);
  EXPECT_FALSE(m.bit(Area::M, 0));
  EXPECT_TRUE(m.bit(Area::M, 1));
  m.write(parse_address("DR100"), 0x12345678);
  EXPECT_EQ(m.reg(Area::R, 100), 0x5678);
  EXPECT_EQ(m.reg(Area::R, 101), 0x1234);
}

TEST(Memory, ThirtyTwoBitCountersTakeTwoWordsEach) {
  Memory m;
  m.write(parse_address("DRC200"), 0x00010002);
  m.write(parse_address("DRC201"), 0xFFFFFFFF);
  EXPECT_EQ(m.read(parse_address("DRC200")), 0x00010002u);
  EXPECT_EQ(m.read(parse_address("RC200")), 0x0002u);  // the low word
  EXPECT_EQ(m.read(parse_address("DRC201")), 0xFFFFFFFFu);
  m.write(parse_address("RC199"), 7);
  EXPECT_EQ(m.read(parse_address("DRC200")), 0x00010002u);
  EXPECT_EQ(Memory::word_count(Area::RC), 200u + 112u);
}

TEST(Memory, DisabledPointsKeepTheirState) {
  Memory m;
  m.set_bit(Area::Y, 3, true);
  m.set_disabled(Area::Y, 3, true);
  m.set_bit(Area::Y, 3, false);
  EXPECT_TRUE(m.bit(Area::Y, 3));
  m.write(parse_address("WY0"), 0);
  EXPECT_TRUE(m.bit(Area::Y, 3));
  m.force_bit(Area::Y, 3, false);  // FATEK 42 RESET still changes it
  EXPECT_FALSE(m.bit(Area::Y, 3));
  EXPECT_TRUE(m.disabled(Area::Y, 3));
  m.set_disabled(Area::Y, 3, false);
  m.set_bit(Area::Y, 3, true);
  EXPECT_TRUE(m.bit(Area::Y, 3));
}

TEST(Memory, ClearKeepsRetentiveRangesAndDisableFlags) {
  Memory m;
  m.set_bit(Area::M, 799, true);
  m.set_bit(Area::M, 800, true);
  m.write(parse_address("R10"), 5);
  m.write(parse_address("R11"), 6);
  m.write(parse_address("DRC210"), 0x10001);
  m.set_disabled(Area::Y, 0, true);
  m.force_bit(Area::Y, 0, true);
  m.clear_non_retentive({{Area::M, 800, 1399}, {Area::R, 11, 11}});
  EXPECT_FALSE(m.bit(Area::M, 799));
  EXPECT_TRUE(m.bit(Area::M, 800));
  EXPECT_EQ(m.reg(Area::R, 10), 0);
  EXPECT_EQ(m.reg(Area::R, 11), 6);
  EXPECT_EQ(m.read(parse_address("DRC210")), 0u);
  EXPECT_TRUE(m.disabled(Area::Y, 0));
  EXPECT_FALSE(m.bit(Area::Y, 0));
}
