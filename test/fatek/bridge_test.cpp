// The FATEK bridge's bus side (fatek::Bridge, no ROS): its YAML, and polling, writing and
// reconnecting against the soft PLC's own FATEK server on loopback TCP. Waits are bounded
// waits on what the bridge reports, never sleeps.
#include <gtest/gtest.h>

#include <condition_variable>
#include <fstream>
#include <functional>
#include <mutex>

#include "../bridge_collector.h"
#include "../reliability/pty_proxy.h"
#include "fatek_link.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/bridge.h"
#include "plc_cell/fatek/server.h"

using namespace plc_cell;
using namespace plc_cell::fatek;

namespace {

// Everything the bridge reports, and bounded waits on it.
class Collector : public bridge_test::Collector {
 public:
  Bridge::Sinks sinks() { return bridge_test::Collector::sinks<Bridge::Sinks>(); }
};

std::unique_ptr<TcpServer> serve(Plc& plc, int port) {
  TcpServerOptions o;
  o.port = port;  // 0: a free one
  auto s = std::make_unique<TcpServer>(plc, o);
  s->start();
  return s;
}

BridgeConfig yaml(const std::string& text) { return parse_bridge_config(YAML::Load(text), "bridge.yaml"); }

BridgeConfig link_to(int port, BridgeConfig cfg) { return bridge_test::loopback_link(port, std::move(cfg)); }

// The error loading text from a file, or "no error".
std::string config_error(const fatek_test::TempDir& dir, const std::string& text, std::string* path) {
  *path = dir.path + "/bridge.yaml";
  std::ofstream(*path) << text;
  try {
    load_bridge_config(*path);
  } catch (const SourceError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(FatekBridgeConfig, SignalsAndGroups) {
  BridgeConfig c = yaml("signals: {start: X0, motor: Y0}\n"
                        "groups:\n  - {name: levels, rate: 5, points: [\"R100:10\", DR200]}\n");
  ASSERT_EQ(c.signals.size(), 2u);
  EXPECT_EQ(c.signals[1].first, "motor");
  EXPECT_EQ(c.signals[1].second, parse_address("Y0"));
  ASSERT_EQ(c.groups.size(), 1u);
  EXPECT_EQ(c.groups[0].name, "levels");
  EXPECT_DOUBLE_EQ(c.groups[0].rate_hz, 5);
  ASSERT_EQ(c.groups[0].spans.size(), 2u);
  EXPECT_EQ(c.groups[0].spans[0].count, 10u);
  // The same under a top-level fatek_bridge: key.
  c = yaml("fatek_bridge:\n  signals: {start: X0}\n");
  EXPECT_EQ(c.signals.size(), 1u);
  EXPECT_TRUE(c.tcp.empty() && c.serial.empty());  // the link is the front end's
}

TEST(FatekBridgeConfig, ErrorsNameFileLineColumnAndKey) {
  fatek_test::TempDir dir;
  std::string f;
  std::string e = config_error(dir, "signals: {start: X0}\npolls: []\n", &f);
  EXPECT_EQ(e, f + ":2:1: error: key 'polls': unknown key (expected one of: groups, signals)");
  e = config_error(dir, "signals:\n  start: R0\n", &f);
  EXPECT_EQ(e, f + ":2:10: error: key 'signals.start': a signal is a single discrete (X, Y, M, S, T, C)");
  e = config_error(dir, "fatek_bridge:\n  signals: {start: X0}\nregisters: []\n", &f);
  EXPECT_EQ(e, f + ":3:1: error: key 'registers': unknown key (expected one of: fatek_bridge)");
  e = config_error(dir, "fatek_bridge:\n  groups:\n    - {name: g, rate: 5, pionts: [R0]}\n", &f);
  EXPECT_EQ(e.rfind(f + ":3:26: error: key 'fatek_bridge.groups[0].pionts': unknown key", 0), 0u) << e;
  e = config_error(dir, "groups: [\n", &f);
  EXPECT_EQ(e.rfind(f + ":2:", 0), 0u) << e;
  EXPECT_NE(e.find("YAML syntax"), std::string::npos) << e;
}

TEST(FatekBridgeConfig, LinkSettingsAreChecked) {
  BridgeConfig c;
  EXPECT_THROW(Bridge(c, {}), Error);  // neither tcp nor serial
  c.tcp = "127.0.0.1:1";
  c.station = 0;
  EXPECT_THROW(Bridge(c, {}), Error);  // a poller never broadcasts
  c.station = 1;
  c.io_rate_hz = 0;
  EXPECT_THROW(Bridge(c, {}), Error);
  c.io_rate_hz = 10;
  c.backoff_max_s = 0.01;  // below the first delay
  EXPECT_THROW(Bridge(c, {}), Error);
  c.backoff_max_s = 1;
  EXPECT_NO_THROW(Bridge(c, {}));
}

TEST(FatekBridge, PollsTheIoImageSignalsAndGroups) {
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "t.il");
  plc.locked([](ScanEngine&, Memory& m) {
    m.set_bit(Area::X, 3, true);
    m.set_bit(Area::Y, 255, true);
    m.set_bit(Area::M, 7, true);
    m.set_reg(Area::R, 100, 1234);
    m.set_reg(Area::R, 101, 5);
    m.set_reg(Area::D, 0, 0xFFFF);
    return 0;
  });
  auto server = serve(plc, 0);
  Collector c;
  Bridge b(link_to(server->port(), yaml("signals: {x3: X3, m7: M7, m8: M8}\n"
                                        "groups:\n  - {name: g, rate: 100, points: [\"R100:2\", D0]}\n")),
           c.sinks());
  EXPECT_EQ(b.io_frames(), 2u);  // one 48 frame for the image and the signals, one status
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && !c.groups.empty(); }));
  {
    const IoResult io = c.io.front();
    ASSERT_TRUE(io.ok) << io.error;
    EXPECT_FALSE(io.run);
    EXPECT_TRUE(io.x[3]);
    EXPECT_FALSE(io.x[2]);
    EXPECT_TRUE(io.y[255]);
    EXPECT_EQ(io.signals, (std::vector<bool>{true, true, false}));
    const GroupResult g = c.groups.front();
    ASSERT_TRUE(g.ok) << g.error;
    EXPECT_EQ(g.values, (std::vector<uint32_t>{1234, 5, 0xFFFF}));
  }

  // RUN, writes, reads and forcing run between polls, on the same link. RUN first: going
  // to RUN clears the registers that are not retentive, R100 among them.
  b.set_run(true);
  EXPECT_EQ(plc.mode(), RunMode::Run);
  b.write(parse_address("R100"), {1234, 77});
  EXPECT_EQ(plc.read(parse_address("R101"), 1)[0], 77u);
  EXPECT_EQ(b.read(parse_address("R100"), 2), (std::vector<uint32_t>{1234, 77}));
  EXPECT_EQ(b.resolve("m7"), parse_address("M7"));  // a signal's name, as the front ends take it
  EXPECT_EQ(b.read(b.resolve("x3"), 1), plc.read(parse_address("X3"), 1));
  EXPECT_THROW(b.read(parse_address("R8071"), 2), Error);  // past the end: refused before the link
  b.force(parse_address("Y5"), true);
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.bit(Area::Y, 5) && m.disabled(Area::Y, 5); }));
  EXPECT_EQ(b.release(nullptr), (std::vector<Address>{parse_address("Y5")}));
  const Address y5 = parse_address("Y5");
  EXPECT_TRUE(b.release(&y5).empty());
  c.clear();
  ASSERT_TRUE(c.wait([&] {
    return !c.io.empty() && c.io.back().run && !c.groups.empty() && c.groups.back().values[1] == 77;
  }));

  const LinkStatus s = b.status();
  EXPECT_TRUE(s.connected);
  EXPECT_EQ(s.reconnects, 1u);
  EXPECT_EQ(s.errors, 0u) << s.last_error;
  EXPECT_GE(s.polls, 2u);
  EXPECT_GT(s.latency_max_ms, 0);
  b.stop();
}

TEST(FatekBridge, ReconnectsWhenTheServerComesBack) {
  Plc plc;
  plc.locked([](ScanEngine&, Memory& m) {
    m.set_reg(Area::R, 0, 1);
    return 0;
  });
  auto server = serve(plc, 0);
  const int port = server->port();
  Collector c;
  Bridge b(link_to(port, yaml("groups: [{name: g, rate: 100, points: [R0]}]")), c.sinks());
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok; }));

  server.reset();  // gone: the poll fails, the link drops, connection attempts fail
  ASSERT_TRUE(c.wait([&] { return c.errors.size() >= 3; })) << "no failed reconnection";
  EXPECT_FALSE(b.status().connected);
  EXPECT_NE(b.status().last_error, "");
  EXPECT_THROW(b.read(parse_address("R0"), 1), CommError);  // a request meanwhile fails at once

  plc.locked([](ScanEngine&, Memory& m) {
    m.set_reg(Area::R, 0, 2);
    return 0;
  });
  server = serve(plc, port);  // back, on the same port
  c.clear();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok && c.groups.back().values[0] == 2; }));
  const LinkStatus s = b.status();
  EXPECT_TRUE(s.connected);
  EXPECT_EQ(s.reconnects, 2u);
  EXPECT_GE(s.errors, 3u);

  // recover() drops a working link on request and connects again at once.
  b.recover();
  EXPECT_EQ(b.status().last_error, "");
  // (A poll that ended just before recover() may still report after it.)
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && c.io.back().ok && b.status().reconnects == 3; }));
  b.stop();
}

TEST(FatekBridge, PollsAStationOnASerialLine) {
  fatek_test::TempDir dir;
  fatek_test::PtyPair pty(dir.path);
  Plc plc;
  plc.write(parse_address("R7"), {42});
  SerialServerOptions so;
  so.line = parse_serial_settings(pty.a + ":115200:7E1");
  so.station = 3;
  SerialServer server(plc, so);
  server.start();
  BridgeConfig cfg = yaml("groups: [{name: g, rate: 50, points: [R7]}]");
  cfg.serial = pty.b + ":115200:7E1";
  cfg.station = 3;
  cfg.timeout_s = 3;
  cfg.io_rate_hz = 50;
  Collector c;
  Bridge b(cfg, c.sinks());
  EXPECT_NE(b.describe().find("station 3"), std::string::npos) << b.describe();
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok; })) << b.status().last_error;
  EXPECT_EQ(c.groups.back().values, (std::vector<uint32_t>{42}));
  b.write(parse_address("R7"), {43});
  ASSERT_TRUE(c.wait([&] { return c.groups.back().ok && c.groups.back().values[0] == 43; }));
  EXPECT_TRUE(b.status().connected);
  b.stop();
  server.stop();
}

// A station that answers late but in order (the soft PLC's serial server behind a proxy
// that holds each reply back 300 ms; ~timeout 200 ms, ~retries 1). Two one-register groups
// have replies alike but for their value: a late reply must never pass for the other
// group's, and once the station answers in time the same link delivers the true values.
// The line is drained until quiet for the timeout, so the replies come between the timeout
// and twice it, 100 ms from either, for a loaded machine's late threads.
TEST(FatekBridge, ALateReplyIsNeverTakenForTheNextRequest) {
  LateDeviceLine proxy(300);
  Plc plc;
  plc.write(parse_address("R0"), {111});
  plc.write(parse_address("R1000"), {222});
  SerialServerOptions so;
  so.line = parse_serial_settings(proxy.device_link() + ":115200:7E1");
  so.station = 1;
  SerialServer server(plc, so);
  server.start();
  BridgeConfig cfg = yaml("groups: [{name: a, rate: 20, points: [R0]}, {name: b, rate: 20, points: [R1000]}]");
  cfg.serial = proxy.client_link() + ":115200:7E1";
  cfg.timeout_s = 0.2;
  cfg.retries = 1;
  cfg.io_rate_hz = 20;
  cfg.backoff_min_s = 0.01;
  cfg.backoff_max_s = 0.05;
  Collector c;
  Bridge b(cfg, c.sinks());
  b.start();
  const auto only_true_values = [&] {
    for (const auto& g : c.groups)
      if (g.ok) EXPECT_EQ(g.values, (std::vector<uint32_t>{g.group == 0 ? 111u : 222u})) << "group " << g.group;
  };
  ASSERT_TRUE(c.wait([&] { return c.errors.size() >= 4; }, 30));
  only_true_values();
  for (const auto& g : c.groups) EXPECT_FALSE(g.ok);
  proxy.set_delay_ms(0);
  c.clear();
  ASSERT_TRUE(c.wait([&] {
    bool a = false, bb = false;
    for (const auto& g : c.groups) (g.group == 0 ? a : bb) |= g.ok;
    return a && bb;
  }, 30)) << b.status().last_error;
  b.stop();
  server.stop();
  only_true_values();
}
