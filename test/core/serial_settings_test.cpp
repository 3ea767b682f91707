#include <gtest/gtest.h>

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

using namespace plc_cell;

TEST(SerialSettings, ParsesDeviceBaudAndFormat) {
  SerialSettings s = parse_serial_settings("/dev/ttyUSB0");
  EXPECT_EQ(s.to_string(), "/dev/ttyUSB0:9600:7E1");  // the FBs default
  s = parse_serial_settings("/dev/ttyS1:921600:8n1");
  EXPECT_EQ(s.baud, 921600);
  EXPECT_EQ(s.data_bits, 8);
  EXPECT_EQ(s.parity, 'N');
  EXPECT_EQ(s.stop_bits, 1);
  EXPECT_EQ(parse_serial_settings("/tmp/a:19200", "8E1").format(), "8E1");
  EXPECT_EQ(parse_serial_settings("/tmp/a:4800:7O2").format(), "7O2");
}

TEST(SerialSettings, RejectsWithTheReason) {
  auto why = [](const std::string& t) {
    try {
      parse_serial_settings(t);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(why(":9600").find("no device"), std::string::npos);
  EXPECT_NE(why("/dev/x:fast").find("baud 'fast' is not a number"), std::string::npos);
  EXPECT_NE(why("/dev/x:1000000").find("outside 1200..921600"), std::string::npos);
  EXPECT_NE(why("/dev/x:9600:9Z1").find("format '9Z1'"), std::string::npos);
}

TEST(SerialSettings, HostPort) {
  std::string h;
  int p;
  parse_host_port("127.0.0.1:500", &h, &p);
  EXPECT_EQ(h, "127.0.0.1");
  EXPECT_EQ(p, 500);
  parse_host_port(":1502", &h, &p);
  EXPECT_EQ(h, "127.0.0.1");
  EXPECT_EQ(p, 1502);
  EXPECT_THROW(parse_host_port("localhost", &h, &p), Error);
  EXPECT_THROW(parse_host_port("h:70000", &h, &p), Error);
  EXPECT_THROW(parse_host_port("h:x", &h, &p), Error);
}
