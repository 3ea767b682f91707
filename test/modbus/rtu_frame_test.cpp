// The RTU framer on a virtual clock (microseconds given by the test).
#include <gtest/gtest.h>

#include "plc_cell/modbus/rtu_frame.h"
#include "wire.h"

namespace plc_cell {
namespace modbus {
namespace {

using test::Bytes;
using Ev = RtuFramer::Event;

TEST(RtuFramer, CrcOfTheSpecificationExample) {
  // Modbus over serial line, CRC example: 02 07 -> CRC 1241H, sent 41 12.
  const uint8_t b[] = {0x02, 0x07};
  EXPECT_EQ(crc16(b, 2), 0x1241);
}

TEST(RtuFramer, T35FromTheBaudRate) {
  EXPECT_EQ(t35_us(9600), 4011);   // 3.5 x 11 bits at 9600 baud
  EXPECT_EQ(t35_us(38400), 1750);  // fixed above 19200 baud
}

TEST(RtuFramer, ServedCodesEndByLengthWithoutWaiting) {
  RtuFramer f(1750, 50000);
  const Bytes a = test::rtu(1, test::hex_bytes("03 0000 0001"));
  f.feed(a.data(), a.size() - 1, 0);
  EXPECT_EQ(f.poll(10), Ev::None);
  f.feed(a.data() + a.size() - 1, 1, 20);
  ASSERT_EQ(f.poll(20), Ev::Frame);  // no silence needed
  EXPECT_EQ(f.frame(), a);
}

TEST(RtuFramer, UnknownCodesEndBySilence) {
  RtuFramer f(1750, 50000);
  const Bytes a = test::rtu(1, test::hex_bytes("2B 0E 01 00"));
  f.feed(a.data(), a.size(), 0);
  EXPECT_EQ(f.poll(1000), Ev::None);
  EXPECT_EQ(f.deadline_us(1000), 1750);
  ASSERT_EQ(f.poll(1750), Ev::Frame);
  EXPECT_EQ(f.frame(), a);
}

TEST(RtuFramer, GarbageIsDroppedAndAFrameAfterItIsFound) {
  RtuFramer f(1750, 50000);
  const Bytes junk = {0x55, 0x01, 0xFF};
  const Bytes a = test::rtu(1, test::hex_bytes("08 0000 1234"));
  f.feed(junk.data(), junk.size(), 0);
  f.feed(a.data(), a.size(), 100);
  ASSERT_EQ(f.poll(2000), Ev::Frame);
  EXPECT_EQ(f.frame(), a);
  EXPECT_EQ(f.garbage_bytes(), 3u);
  // A frame cut mid-way: nothing, then dropped as garbage after the frame timeout.
  f.feed(a.data(), 4, 10000);
  EXPECT_EQ(f.poll(12000), Ev::None);
  EXPECT_EQ(f.poll(60000), Ev::Garbage);
  EXPECT_EQ(f.garbage_bytes(), 7u);
  EXPECT_FALSE(f.in_frame());
}

TEST(RtuFramer, BadCrcIsNeverAFrame) {
  RtuFramer f(1750, 50000);
  Bytes a = test::rtu(1, test::hex_bytes("03 0000 0001"));
  a[7] ^= 1;
  f.feed(a.data(), a.size(), 0);
  EXPECT_EQ(f.poll(3000), Ev::None);
  EXPECT_EQ(f.poll(50000), Ev::Garbage);
}

TEST(RtuFramer, AnOversizedRunIsDropped) {
  RtuFramer f(1750, 50000);
  const Bytes big(600, 0x11);
  f.feed(big.data(), big.size(), 0);
  EXPECT_EQ(f.poll(1), Ev::Garbage);
  EXPECT_FALSE(f.in_frame());
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
