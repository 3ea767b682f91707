// One endpoint text, HOST:PORT or a serial device path, to a master's transport
// (io/endpoint.h): what each text means, the reason a bad one is refused, and bytes that
// reach the other end over loopback TCP and over a pty.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdlib>
#include <functional>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/io/endpoint.h"

namespace plc_cell {
namespace {

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "accepted";
}

std::string refusal(const std::string& text) {
  return error_of([&] { client_transport(text); });
}

const LineDefaults kTri{"8N1", 38400};

TEST(Endpoint, HostPortIsTcp) {
  Endpoint e = parse_endpoint("127.0.0.1:500");
  EXPECT_FALSE(e.serial);
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, 500);
  e = parse_endpoint(":9080", kTri);
  EXPECT_FALSE(e.serial);
  EXPECT_EQ(e.host, "127.0.0.1");
  EXPECT_EQ(e.port, 9080);
  EXPECT_EQ(parse_endpoint("plc.local:65535").host, "plc.local");
}

TEST(Endpoint, ADevicePathIsASerialLineWithTheGivenDefaults) {
  Endpoint e = parse_endpoint("/dev/ttyUSB0");
  ASSERT_TRUE(e.serial);
  EXPECT_EQ(e.serial->to_string(), "/dev/ttyUSB0:9600:7E1");  // the FBs' line
  EXPECT_EQ(parse_endpoint("/dev/ttyUSB0", kTri).serial->to_string(), "/dev/ttyUSB0:38400:8N1");
  EXPECT_EQ(parse_endpoint("/dev/ttyUSB0:19200", kTri).serial->to_string(), "/dev/ttyUSB0:19200:8N1");
  EXPECT_EQ(parse_endpoint("/dev/ttyS1:4800:8E1", kTri).serial->to_string(), "/dev/ttyS1:4800:8E1");
  // A relative path is a path too: a '/' before the first ':'.
  EXPECT_EQ(parse_endpoint("./ttyV0:9600").serial->device, "./ttyV0");
}

TEST(Endpoint, ABadTextIsRefusedSayingWhatIsWrong) {
  EXPECT_EQ(refusal(""), "empty endpoint: expected HOST:PORT or a serial device path such as "
                         "/dev/ttyUSB0[:BAUD[:FORMAT]]");
  EXPECT_EQ(refusal("localhost"), "endpoint 'localhost': expected HOST:PORT or a serial device path such as "
                                  "/dev/ttyUSB0[:BAUD[:FORMAT]]");
  EXPECT_EQ(refusal("ttyUSB0"), "endpoint 'ttyUSB0': expected HOST:PORT or a serial device path such as "
                                "/dev/ttyUSB0[:BAUD[:FORMAT]]");
  EXPECT_EQ(refusal("plc:"), "endpoint 'plc:': port '' is not a number (expected HOST:PORT, e.g. 127.0.0.1:500)");
  EXPECT_EQ(refusal("plc:fast"),
            "endpoint 'plc:fast': port 'fast' is not a number (expected HOST:PORT, e.g. 127.0.0.1:500)");
  EXPECT_EQ(refusal("plc:70000"), "endpoint 'plc:70000': port '70000' is not 0..65535");
  EXPECT_EQ(refusal("plc:0"), "endpoint 'plc:0': port 0: a client needs the port its device listens on (1..65535)");
  EXPECT_EQ(refusal("/dev/ttyUSB0:fast"), "serial port '/dev/ttyUSB0:fast': baud 'fast' is not a number");
  EXPECT_EQ(refusal("/nonexistent/ttyUSB9"), "endpoint '/nonexistent/ttyUSB9': no such device /nonexistent/ttyUSB9");
  EXPECT_EQ(refusal("/nonexistent/ttyUSB9:19200:8N1"),
            "endpoint '/nonexistent/ttyUSB9:19200:8N1': no such device /nonexistent/ttyUSB9");
  const std::string file = std::string(PLC_CELL_SOURCE_DIR) + "/package.xml";
  EXPECT_EQ(refusal(file), "endpoint '" + file + "': " + file + " is not a serial device (not a character device)");
}

TEST(Endpoint, TcpBytesReachTheListener) {
  const int ls = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t len = sizeof sa;
  ASSERT_EQ(::bind(ls, reinterpret_cast<sockaddr*>(&sa), len), 0);
  ASSERT_EQ(::listen(ls, 1), 0);
  ASSERT_EQ(::getsockname(ls, reinterpret_cast<sockaddr*>(&sa), &len), 0);
  const std::string port = std::to_string(ntohs(sa.sin_port));
  const auto t = client_transport("127.0.0.1:" + port);
  EXPECT_EQ(t->describe(), "tcp 127.0.0.1:" + port);
  EXPECT_FALSE(t->is_open());  // connected by the first transaction
  t->send("@00", 1000);
  const int peer = ::accept(ls, nullptr, nullptr);
  ASSERT_GE(peer, 0);
  char buf[8] = {};
  ASSERT_TRUE(wait_readable(peer, 5000));
  EXPECT_EQ(::read(peer, buf, sizeof buf), 3);
  EXPECT_EQ(std::string(buf, 3), "@00");
  ::close(peer);
  ::close(ls);
}

TEST(Endpoint, SerialBytesReachTheOtherSideOfAPty) {
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC);
  ASSERT_GE(master, 0);
  ASSERT_EQ(::grantpt(master), 0);
  ASSERT_EQ(::unlockpt(master), 0);
  const std::string device = ::ptsname(master);
  const auto t = client_transport(device + ":19200", kTri);
  EXPECT_EQ(t->describe(), "serial " + device + ":19200:8N1");
  t->send("IR", 1000);
  char buf[8] = {};
  ASSERT_TRUE(wait_readable(master, 5000));
  EXPECT_EQ(::read(master, buf, sizeof buf), 2);
  EXPECT_EQ(std::string(buf, 2), "IR");
  t->close();
  ::close(master);
}

}  // namespace
}  // namespace plc_cell
