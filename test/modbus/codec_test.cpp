// Every type in every byte/word order: known wire images and round trips.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/modbus/codec.h"

namespace plc_cell {
namespace modbus {
namespace {

const Order kOrders[] = {Order::Big, Order::Little};

Encoding enc(PointType t, Order bo, Order wo) {
  Encoding e;
  e.type = t;
  e.byte_order = bo;
  e.word_order = wo;
  return e;
}

TEST(Codec, Float32WireImagesInAllFourOrders) {
  // 1.5f = 0x3FC00000: A=3F B=C0 C=00 D=00. Use 0x3FC00001-ish to tell C and D apart.
  const uint64_t raw = 0x3FC01234;  // A=3F B=C0 C=12 D=34
  struct {
    Order bo, wo;
    uint16_t r0, r1;
    const char* name;
  } rows[] = {{Order::Big, Order::Big, 0x3FC0, 0x1234, "ABCD"},
              {Order::Big, Order::Little, 0x1234, 0x3FC0, "CDAB"},
              {Order::Little, Order::Big, 0xC03F, 0x3412, "BADC"},
              {Order::Little, Order::Little, 0x3412, 0xC03F, "DCBA"}};
  for (const auto& r : rows) {
    uint16_t regs[2];
    pack(enc(PointType::Float32, r.bo, r.wo), raw, regs);
    EXPECT_EQ(regs[0], r.r0) << r.name;
    EXPECT_EQ(regs[1], r.r1) << r.name;
    EXPECT_EQ(unpack(enc(PointType::Float32, r.bo, r.wo), regs), raw) << r.name;
  }
}

TEST(Codec, SixtyFourBitWordOrder) {
  uint16_t regs[4];
  pack(enc(PointType::UInt64, Order::Big, Order::Big), 0x0102030405060708ull, regs);
  EXPECT_EQ(regs[0], 0x0102);
  EXPECT_EQ(regs[3], 0x0708);
  pack(enc(PointType::UInt64, Order::Big, Order::Little), 0x0102030405060708ull, regs);
  EXPECT_EQ(regs[0], 0x0708);
  EXPECT_EQ(regs[3], 0x0102);
  pack(enc(PointType::UInt64, Order::Little, Order::Little), 0x0102030405060708ull, regs);
  EXPECT_EQ(regs[0], 0x0807);
  EXPECT_EQ(regs[3], 0x0201);
}

TEST(Codec, EveryTypeRoundTripsInEveryOrder) {
  struct Case {
    PointType t;
    double v;
  } cases[] = {{PointType::Int16, -12345},       {PointType::UInt16, 54321},
               {PointType::Int32, -123456789},   {PointType::UInt32, 4000000000.0},
               {PointType::Float32, -3.25f},     {PointType::Int64, -1234567890123.0},
               {PointType::UInt64, 9007199254740993.0 - 1},  // 2^53, exact
               {PointType::Float64, 2.718281828459045}, {PointType::Bool, 1}};
  for (const auto& c : cases)
    for (Order bo : kOrders)
      for (Order wo : kOrders) {
        const Encoding e = enc(c.t, bo, wo);
        uint16_t regs[4] = {0, 0, 0, 0};
        const uint64_t raw = to_raw(c.t, c.v);
        if (c.t == PointType::Bool) regs[0] = uint16_t(raw);
        else pack(e, raw, regs);
        const Value v = decode(e, regs);
        EXPECT_EQ(v.as_double(), c.v) << point_type_name(c.t) << " bo=" << int(bo) << " wo=" << int(wo);
      }
}

TEST(Codec, ExtremesAndExactIntegers) {
  const Encoding e = enc(PointType::Int64, Order::Little, Order::Little);
  uint16_t regs[4];
  pack(e, uint64_t(INT64_MIN), regs);
  EXPECT_EQ(decode(e, regs).as_int64(), INT64_MIN);
  const Encoding u = enc(PointType::UInt64, Order::Big, Order::Little);
  pack(u, UINT64_MAX, regs);
  EXPECT_EQ(decode(u, regs).as_uint64(), UINT64_MAX);
  EXPECT_THROW(to_raw(PointType::Float32, NAN), Error);  // never written to a device
}

TEST(Codec, ScaleOffsetAndRangeChecks) {
  EXPECT_EQ(to_raw(PointType::UInt16, 23.5, 0.1, 0), 235u);
  EXPECT_EQ(to_raw(PointType::Int16, -40, 0.5, -50), 20u);
  EXPECT_EQ(uint16_t(to_raw(PointType::Int16, -1)), 0xFFFF);
  EXPECT_THROW(to_raw(PointType::UInt16, 65536), Error);
  EXPECT_THROW(to_raw(PointType::UInt16, -1), Error);
  EXPECT_THROW(to_raw(PointType::Int32, 2147483648.0), Error);
  EXPECT_THROW(to_raw(PointType::UInt64, 18446744073709551616.0), Error);
  EXPECT_THROW(to_raw(PointType::Float32, 1e39), Error);
  // The value as written (no six decimals of an integer), the type and its bounds.
  try {
    to_raw(PointType::UInt16, 70000);
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "value 70000 does not fit uint16 (0..65535)");
  }
  EXPECT_EQ(format_value(70000), "70000");
  EXPECT_EQ(format_value(0.1), "0.1");
  EXPECT_EQ(format_value(-2.5e-7), "-2.5e-07");
  EXPECT_THROW(parse_point_type("float16"), Error);
  EXPECT_EQ(parse_point_type("float64"), PointType::Float64);
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
