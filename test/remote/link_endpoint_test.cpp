// The links take their endpoint text as io/endpoint.h reads it: HOST:PORT or a serial
// device, each protocol's line by default (FATEK 9600 7E1, TRi 38400 8N1), and a text that
// names no reachable kind of endpoint refused when the link is made, saying why.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <unistd.h>

#include <cstdlib>

#include "plc_cell/remote/fatek_link.h"
#include "plc_cell/remote/tri_link.h"
#include "remote_fixture.h"

namespace plc_cell {
namespace {

using remote_test::error_of;

template <class Link, class Options>
std::string refusal(const std::string& endpoint) {
  Options o;
  o.endpoint = endpoint;
  return error_of([&] { Link link(o); });
}

// A pty's device side, for a link that must find its device at once.
struct Pty {
  Pty() : master(::posix_openpt(O_RDWR | O_NOCTTY | O_CLOEXEC)) {
    if (master >= 0 && ::grantpt(master) == 0 && ::unlockpt(master) == 0) device = ::ptsname(master);
  }
  ~Pty() { ::close(master); }
  int master;
  std::string device;
};

TEST(LinkEndpoint, EachProtocolsLineByDefault) {
  Pty pty;
  ASSERT_FALSE(pty.device.empty());
  remote::FatekLinkOptions f;
  f.endpoint = pty.device;
  EXPECT_EQ(remote::FatekLink(f).describe(), "FATEK serial " + pty.device + ":9600:7E1 station 1");
  remote::TriLinkOptions t;
  t.endpoint = pty.device;
  EXPECT_EQ(remote::TriLink(t).describe(), "TRi serial " + pty.device + ":38400:8N1 ID 01");
  t.endpoint = pty.device + ":9600";
  EXPECT_EQ(remote::TriLink(t).describe(), "TRi serial " + pty.device + ":9600:8N1 ID 01");
  t.endpoint = ":9080";
  EXPECT_EQ(remote::TriLink(t).describe(), "TRi tcp 127.0.0.1:9080 ID 01");
}

TEST(LinkEndpoint, ABadEndpointIsRefusedWhenTheLinkIsMade) {
  using Fatek = remote::FatekLink;
  using FatekOptions = remote::FatekLinkOptions;
  using Tri = remote::TriLink;
  using TriOptions = remote::TriLinkOptions;
  EXPECT_EQ((refusal<Fatek, FatekOptions>("/nonexistent/ttyUSB0")),
            "endpoint '/nonexistent/ttyUSB0': no such device /nonexistent/ttyUSB0");
  EXPECT_EQ((refusal<Tri, TriOptions>("/nonexistent/ttyUSB0:38400")),
            "endpoint '/nonexistent/ttyUSB0:38400': no such device /nonexistent/ttyUSB0");
  EXPECT_EQ((refusal<Fatek, FatekOptions>("plc:0")),
            "endpoint 'plc:0': port 0: a client needs the port its device listens on (1..65535)");
  EXPECT_EQ((refusal<Tri, TriOptions>("plc:99999")), "endpoint 'plc:99999': port '99999' is not 0..65535");
  EXPECT_NE((refusal<Tri, TriOptions>("")).find("empty endpoint"), std::string::npos);
  EXPECT_NE((refusal<Fatek, FatekOptions>("ttyUSB0")).find("expected HOST:PORT or a serial device path"),
            std::string::npos);
}

}  // namespace
}  // namespace plc_cell
