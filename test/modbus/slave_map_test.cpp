// The address maps, against the manual's tables [M:5023-5110].
#include <gtest/gtest.h>

#include "plc_cell/core/memory.h"
#include "plc_cell/modbus/slave_map.h"

namespace plc_cell {
namespace modbus {
namespace {

modbus::Run at(const Memory& m, Table t, uint32_t addr, uint32_t n = 1) {
  modbus::Run r;
  EXPECT_TRUE(resolve(m, t, addr, n, &r)) << addr;
  return r;
}
bool mapped(const Memory& m, Table t, uint32_t addr, uint32_t n = 1) {
  modbus::Run r;
  return resolve(m, t, addr, n, &r);
}

TEST(SlaveMap, DefaultCoilsFollowTheManual) {
  Memory m;
  struct {
    uint32_t addr; Area area; uint32_t index;
  } rows[] = {{0, Area::Y, 0}, {255, Area::Y, 255}, {1000, Area::X, 0}, {1255, Area::X, 255},
              {2000, Area::M, 0}, {4001, Area::M, 2001}, {6000, Area::S, 0}, {6999, Area::S, 999},
              {9000, Area::T, 0}, {9255, Area::T, 255}, {9500, Area::C, 0}, {9755, Area::C, 255}};
  for (const auto& r : rows) {
    const modbus::Run run = at(m, Table::Coils, r.addr);
    EXPECT_EQ(run.area, r.area) << r.addr;
    EXPECT_EQ(run.index, r.index) << r.addr;
  }
  for (uint32_t gap : {256u, 999u, 1256u, 1999u, 4002u, 5999u, 7000u, 8999u, 9256u, 9499u, 9756u, 65535u})
    EXPECT_FALSE(mapped(m, Table::Coils, gap)) << gap;
  EXPECT_TRUE(mapped(m, Table::Coils, 0, 256));
  EXPECT_FALSE(mapped(m, Table::Coils, 0, 257));  // Y255 then a gap: never spans areas
}

TEST(SlaveMap, DefaultRegistersFollowTheManual) {
  Memory m;
  struct {
    uint32_t addr; Area area; uint32_t index;
  } rows[] = {{0, Area::R, 0},      {4167, Area::R, 4167}, {5000, Area::R, 5000}, {5998, Area::R, 5998},
              {6000, Area::D, 0},   {8998, Area::D, 2998}, {9000, Area::RT, 0},   {9255, Area::RT, 255},
              {9500, Area::RC, 0},  {9699, Area::RC, 199},
              {9700, Area::RC, rc_word_index(200)},      // C200 low word
              {9701, Area::RC, rc_word_index(200) + 1},  // C200 high word
              {9811, Area::RC, rc_word_index(255) + 1}};
  for (const auto& r : rows) {
    const modbus::Run run = at(m, Table::HoldingRegisters, r.addr);
    EXPECT_EQ(run.area, r.area) << r.addr;
    EXPECT_EQ(run.index, r.index) << r.addr;
  }
  for (uint32_t gap : {4168u, 4999u, 5999u, 8999u, 9256u, 9499u, 9812u, 65535u})
    EXPECT_FALSE(mapped(m, Table::HoldingRegisters, gap)) << gap;
  // No 1x / 3x space by default.
  EXPECT_FALSE(mapped(m, Table::DiscreteInputs, 0));
  EXPECT_FALSE(mapped(m, Table::InputRegisters, 0));
}

TEST(SlaveMap, UserDefinedMapIsTheManualsExample) {
  Memory m;
  const uint16_t regs[] = {0xA55A, 0, 1000, 100, 10, 1100, 50, 50, 1000, 10, 100, 2000, 200};
  for (uint32_t i = 0; i < 13; ++i) m.set_reg(Area::R, 3968 + i, regs[i]);
  EXPECT_TRUE(user_map_enabled(m));
  modbus::Run r = at(m, Table::Coils, 0);  // 000001 <-> M1000
  EXPECT_EQ(r.area, Area::M);
  EXPECT_EQ(r.index, 1000u);
  EXPECT_TRUE(mapped(m, Table::Coils, 0, 100));
  EXPECT_FALSE(mapped(m, Table::Coils, 0, 101));
  EXPECT_FALSE(mapped(m, Table::Coils, 2000));  // the default map is off
  r = at(m, Table::DiscreteInputs, 10);  // 100011 <-> M1100
  EXPECT_EQ(r.index, 1100u);
  EXPECT_EQ(at(m, Table::DiscreteInputs, 59).index, 1149u);
  EXPECT_FALSE(mapped(m, Table::DiscreteInputs, 60));
  r = at(m, Table::InputRegisters, 50);  // 300051 <-> R1000
  EXPECT_EQ(r.area, Area::R);
  EXPECT_EQ(r.index, 1000u);
  EXPECT_FALSE(mapped(m, Table::InputRegisters, 60));
  r = at(m, Table::HoldingRegisters, 100);  // 400101 <-> R2000
  EXPECT_EQ(r.index, 2000u);
  EXPECT_EQ(at(m, Table::HoldingRegisters, 299).index, 2199u);
  EXPECT_FALSE(mapped(m, Table::HoldingRegisters, 300));
  EXPECT_FALSE(mapped(m, Table::HoldingRegisters, 99));
}

TEST(SlaveMap, InputGroupsIgnoreR3968AndBadGroupsMapNothing) {
  Memory m;
  m.set_reg(Area::R, 3972, 0);
  m.set_reg(Area::R, 3973, 5);
  m.set_reg(Area::R, 3974, 3);
  EXPECT_FALSE(user_map_enabled(m));
  EXPECT_EQ(at(m, Table::DiscreteInputs, 2).index, 7u);  // "Don't care R3968"
  EXPECT_EQ(at(m, Table::Coils, 0).area, Area::Y);        // default still applies to 0x
  m.set_reg(Area::R, 3968, 0xA55A);
  m.set_reg(Area::R, 3979, 3800);
  m.set_reg(Area::R, 3980, 41);  // R3800 + 41 passes R3839
  EXPECT_FALSE(mapped(m, Table::HoldingRegisters, 0));
  m.set_reg(Area::R, 3980, 40);
  EXPECT_TRUE(mapped(m, Table::HoldingRegisters, 0, 40));
  m.set_reg(Area::R, 3971, 0);  // count 0: no coil space at all
  EXPECT_FALSE(mapped(m, Table::Coils, 0));
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
