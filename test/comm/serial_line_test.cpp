// A serial line held by its path: when the device goes away (here the socat pty pair is
// stopped) the line says so, and when a device is back at the path it is reopened.
#include <gtest/gtest.h>

#include <poll.h>
#include <unistd.h>

#include <memory>

#include "../fatek/fatek_link.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_line.h"

using namespace plc_cell;

TEST(SerialLine, ReopensTheDeviceAtItsPathWhenItIsBack) {
  fatek_test::TempDir dir;
  auto pty = std::make_unique<fatek_test::PtyPair>(dir.path);
  const std::string device = pty->a, peer_device = pty->b;
  SerialLine line(parse_serial_settings(device + ":115200:8N1"));
  ASSERT_TRUE(line.open()) << line.last_error();
  EXPECT_EQ(line.reopened(), 0u);

  pty.reset();  // the device disappears: the line hangs up
  pollfd p{line.fd(), POLLIN, 0};
  ASSERT_EQ(::poll(&p, 1, 5000), 1);
  EXPECT_NE(p.revents & (POLLHUP | POLLERR), 0);
  line.lost("hang-up");
  EXPECT_FALSE(line.is_open());
  EXPECT_EQ(line.last_error(), "serial device lost: hang-up");
  EXPECT_FALSE(line.open());  // nothing at the path
  EXPECT_NE(line.last_error().find("cannot open"), std::string::npos) << line.last_error();

  pty = std::make_unique<fatek_test::PtyPair>(dir.path);  // back, at the same path
  ASSERT_TRUE(line.open()) << line.last_error();
  EXPECT_EQ(line.reopened(), 1u);
  EXPECT_EQ(line.last_error(), "serial device back");
  const int peer = open_serial_line(parse_serial_settings(peer_device + ":115200:8N1"));
  ASSERT_EQ(::write(peer, "ok", 2), 2);
  char buf[4] = {};
  ASSERT_TRUE(fatek::wait_readable(line.fd(), 5000));
  EXPECT_EQ(::read(line.fd(), buf, sizeof buf), 2);
  EXPECT_EQ(std::string(buf, 2), "ok");
  ::close(peer);
}

TEST(SerialLine, AFirstOpenThatFailsSaysWhy) {
  SerialLine line(parse_serial_settings("/tmp/plc_cell_no_such_tty:9600:7E1"));
  EXPECT_FALSE(line.open());
  EXPECT_EQ(line.reopened(), 0u);
  EXPECT_THROW(line.open_or_throw(), Error);
  EXPECT_NE(line.last_error().find("/tmp/plc_cell_no_such_tty"), std::string::npos);
}
