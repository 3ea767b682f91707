// The TRi bridge's bus side (tri::Bridge, no ROS): point names, the poll plan and its
// frame counts, polling, writing, forcing, halt/resume and reconnecting against the soft
// PLC's own host-link slave over loopback TCP and a socat pty pair, and the client's
// errors on bad replies. Waits are bounded waits on what the bridge reports, never sleeps.
#include <gtest/gtest.h>

#include <deque>
#include <fstream>
#include <map>

#include "../bridge_collector.h"
#include "../fatek/fatek_link.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/tri/bridge.h"
#include "plc_cell/tri/frame.h"
#include "plc_cell/tri/server.h"

using namespace plc_cell;
using namespace plc_cell::tri;

namespace {

class Collector : public bridge_test::Collector {
 public:
  Bridge::Sinks sinks() { return bridge_test::Collector::sinks<Bridge::Sinks>(); }
};

std::unique_ptr<TcpServer> serve(Plc& plc, int port) {
  auto s = std::make_unique<TcpServer>(plc, "127.0.0.1", port, ServerOptions{});
  s->start();
  return s;
}

BridgeConfig yaml(const std::string& text) { return parse_bridge_config(YAML::Load(text), "tri.yaml"); }

BridgeConfig link_to(int port, BridgeConfig cfg) { return bridge_test::loopback_link(port, std::move(cfg)); }

Address A(const char* t) { return parse_address(t); }

// A transport that answers every request with the next scripted reply (no sockets).
class Scripted : public Transport {
 public:
  explicit Scripted(std::deque<std::string> replies) : replies_(std::move(replies)) {}
  void open() override { open_ = true; }
  void close() override { open_ = false; }
  bool is_open() const override { return open_; }
  void send(const std::string& b, int) override {
    sent.push_back(b);
    if (!replies_.empty()) {
      pending_ = replies_.front();
      replies_.pop_front();
    }
  }
  size_t recv(char* buf, size_t n, int) override {
    const size_t k = std::min(n, pending_.size());
    pending_.copy(buf, k);
    pending_.erase(0, k);
    return k;
  }
  std::string describe() const override { return "scripted"; }
  std::vector<std::string> sent;

 private:
  std::deque<std::string> replies_;
  std::string pending_;
  bool open_ = true;
};

std::string mp(int id, const std::string& body) {
  Frame f;
  f.multipoint = true;
  f.id = id;
  f.body = body;
  return encode_frame(f);
}

}  // namespace

TEST(TriPoints, TriNamesAndPlcNodeAddresses) {
  EXPECT_EQ(parse_point("INPUT[3]"), A("WX32"));
  EXPECT_EQ(parse_point("OUTPUT[1]"), A("WY0"));
  EXPECT_EQ(parse_point("RELAY[7]"), A("WM96"));
  EXPECT_EQ(parse_point("DM[100]"), A("D99"));
  EXPECT_EQ(parse_point("A"), A("DR3760"));
  EXPECT_EQ(parse_point("z"), A("DR3810"));
  EXPECT_EQ(parse_point("HSCPV[2]"), A("DR4100"));
  EXPECT_EQ(parse_point("TIMERPV[2]"), A("RT51"));
  EXPECT_EQ(parse_point("TIMERSV[1]"), A("R3600"));
  EXPECT_EQ(parse_point("CTRPV[1]"), A("RC0"));
  EXPECT_EQ(parse_point("CTRSV[64]"), A("R3727"));
  EXPECT_EQ(parse_point("ADC[8]"), A("R3847"));
  EXPECT_EQ(parse_point("DAC[1]"), A("R3904"));
  EXPECT_EQ(parse_point("PWM[4]"), A("R3815"));
  EXPECT_THROW(parse_point("PWM[5]"), Error);
  EXPECT_EQ(parse_point("EEPROM[1]"), A("F0"));
  EXPECT_EQ(parse_point("X2"), A("X2"));  // input 3, as plc_node names it
  EXPECT_EQ(parse_point("T50"), A("T50"));  // timer 1's contact
  EXPECT_THROW(parse_point("DM[4001]"), Error);
  EXPECT_THROW(parse_point("FOO[1]"), Error);
  EXPECT_THROW(parse_point("X256"), Error);
  EXPECT_THROW(parse_point("T0"), Error);  // not a TRi timer
  EXPECT_THROW(parse_point("R0"), Error);
  try {
    parse_point("D4000");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("D0-D3999 (DM)"), std::string::npos) << e.what();
  }
}

TEST(TriPoints, ConfigSchema) {
  BridgeConfig c = yaml("tri_bridge:\n  io: {inputs: 32, outputs: 16}\n  signals: {start: X0, lamp: Y1}\n"
                        "  groups:\n    - {name: dm, rate: 5, points: [\"DM[1]:4\", A, \"TIMERPV[1]:2\"]}\n");
  EXPECT_EQ(c.inputs, 32u);
  ASSERT_EQ(c.signals.size(), 2u);
  ASSERT_EQ(c.groups.size(), 1u);
  ASSERT_EQ(c.groups[0].spans.size(), 3u);
  EXPECT_EQ(c.groups[0].spans[0].start, A("D0"));
  EXPECT_EQ(c.groups[0].spans[0].count, 4u);
  EXPECT_EQ(c.groups[0].text, "DM[1]:4,A,TIMERPV[1]:2");
  EXPECT_THROW(yaml("signals: {s: M600}\n"), SourceError);  // relays end at M511
  EXPECT_THROW(yaml("groups: [{name: g, points: [\"R0\"]}]\n"), SourceError);
  EXPECT_THROW(yaml("io: {inputs: 10}\n"), SourceError);
  EXPECT_THROW(yaml("io: {outputs: 0}\n"), SourceError);
  EXPECT_THROW(yaml("polls: []\n"), SourceError);
}

TEST(TriPollPlan, NeighboursAreCoalesced) {
  // Discretes: one RVS frame per word of 16 points, however many are asked.
  EXPECT_EQ(plan_poll({{A("WX0"), 1}, {A("X3"), 1}, {A("X15"), 1}}).requests.size(), 1u);
  EXPECT_EQ(plan_poll({{A("X0"), 32}}).requests.size(), 2u);
  EXPECT_EQ(plan_poll({{A("WX8"), 1}}).requests.size(), 2u);  // straddles INPUT[1] and INPUT[2]
  // ADC channels: one RA; EEPROM words: RXI runs of up to 32, through small gaps.
  EXPECT_EQ(plan_poll({{A("R3840"), 8}}).requests.size(), 1u);
  EXPECT_EQ(plan_poll({{A("F0"), 40}}).requests.size(), 2u);
  EXPECT_EQ(plan_poll({{A("F0"), 2}, {A("F5"), 2}}).requests.size(), 1u);
  EXPECT_EQ(plan_poll({{A("F0"), 1}, {A("F100"), 1}}).requests.size(), 2u);
  // DM, A-Z, PVs: one frame each (the protocol has no multi-word read of them); the
  // same element twice is read once.
  EXPECT_EQ(plan_poll({{A("D0"), 3}, {A("D1"), 1}}).requests.size(), 3u);
  EXPECT_EQ(plan_poll({{A("R3760"), 1}, {A("R3761"), 1}, {A("DR3760"), 1}}).requests.size(), 1u);
  EXPECT_EQ(plan_poll({{A("RT50"), 2}, {A("RC0"), 2}}).requests.size(), 4u);
}

TEST(TriClient, RepliesAreChecked) {
  Request rvd;
  rvd.cmd = Cmd::ReadDm;
  rvd.a = 100;
  const std::string good = mp(1, "RVD3039");
  std::string bad_fcs = good;
  bad_fcs[bad_fcs.size() - 3] ^= 1;  // last FCS digit
  auto client = [](std::deque<std::string> r, Scripted** t) {
    auto s = std::make_unique<Scripted>(std::move(r));
    *t = s.get();
    ClientOptions o;
    o.timeout_ms = 50;
    o.retries = 0;
    return std::make_unique<Client>(std::move(s), o);
  };
  Scripted* t = nullptr;
  auto c = client({good}, &t);
  EXPECT_EQ(c->transact(rvd).values, (std::vector<uint32_t>{0x3039}));
  EXPECT_EQ(t->sent.at(0), mp(1, "RVD0064"));  // multi-point, with its FCS
  c = client({bad_fcs}, &t);
  try {
    c->transact(rvd);
    FAIL();
  } catch (const CommError& e) {
    EXPECT_NE(std::string(e.what()).find("bad FCS"), std::string::npos) << e.what();
  }
  c = client({mp(1, "ER03")}, &t);
  try {
    c->transact(rvd);
    FAIL();
  } catch (const PlcError& e) {
    EXPECT_EQ(e.code, ErrorCode::OutOfRange);
    EXPECT_EQ(std::string(e.what()), "TRi error ER03 (out of range) to RVD0064");
  }
  c = client({mp(1, "FE")}, &t);
  try {
    c->transact(rvd);
    FAIL();
  } catch (const CommError& e) {
    EXPECT_NE(std::string(e.what()).find("framing error"), std::string::npos) << e.what();
  }
  c = client({mp(1, "RVIX")}, &t);  // not an answer to RVD
  EXPECT_THROW(c->transact(rvd), CommError);
  c = client({mp(2, "RVD3039")}, &t);  // another device's: not ours, so no answer in time
  try {
    c->transact(rvd);
    FAIL();
  } catch (const CommError& e) {
    EXPECT_NE(std::string(e.what()).find("no answer to RVD0064"), std::string::npos) << e.what();
  }
  // A retry after a garbled answer.
  auto s = std::make_unique<Scripted>(std::deque<std::string>{"@01RVD3#\r", good});
  Scripted* raw = s.get();
  ClientOptions o;
  o.timeout_ms = 50;
  o.retries = 1;
  Client r(std::move(s), o);
  EXPECT_EQ(r.transact(rvd).values, (std::vector<uint32_t>{0x3039}));
  EXPECT_EQ(raw->sent.size(), 2u);
  EXPECT_EQ(r.requests(), 2u);
}

TEST(TriBridge, PollsTheCellInTheFramesPlanned) {
  Plc plc;
  plc.locked([](ScanEngine&, Memory& m) {
    m.set_bit(Area::X, 3, true);
    m.set_bit(Area::Y, 1, true);
    m.set_bit(Area::M, 7, true);
    m.set_reg(Area::D, 0, 1234);
    m.set_reg(Area::D, 1, 5);
    m.set_reg(Area::R, 3760, 0x0001);  // A = 0x00020001
    m.set_reg(Area::R, 3761, 0x0002);
    m.set_reg(Area::R, 3840, 11);  // ADC 1, 2
    m.set_reg(Area::R, 3841, 22);
    m.set_reg(Area::F, 0, 7);
    m.set_reg(Area::R, 3813, 9500);  // PWM 2 at 95.00 %
    return 0;
  });
  auto server = serve(plc, 0);
  Collector c;
  Bridge b(link_to(server->port(), yaml("signals: {x3: X3, y1: Y1, m7: M7, m8: M8}\n"
                                        "groups:\n  - {name: g, rate: 100, points: "
                                        "[\"DM[1]:2\", A, \"ADC[1]:2\", \"EEPROM[1]:3\", \"TIMERPV[1]\", \"PWM[2]\"]}\n")),
           c.sinks());
  // INPUT[1], OUTPUT[1] (the signals X3 and Y1 are in them) and RELAY[1] for M7 and M8.
  EXPECT_EQ(b.io_frames(), 3u);
  // DM[1], DM[2], RVI A, one RA, one RXI, RVS 06 01, RVS 0D 02.
  EXPECT_EQ(b.group_frames(0), 7u);
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && !c.groups.empty(); }));
  {
    const IoResult io = c.io.front();
    ASSERT_TRUE(io.ok) << io.error;
    EXPECT_TRUE(io.run);
    ASSERT_EQ(io.x.size(), 256u);
    EXPECT_TRUE(io.x[3]);
    EXPECT_FALSE(io.x[2]);
    EXPECT_TRUE(io.y[1]);
    EXPECT_EQ(io.signals, (std::vector<bool>{true, true, true, false}));
    const GroupResult g = c.groups.front();
    ASSERT_TRUE(g.ok) << g.error;
    EXPECT_EQ(g.values, (std::vector<uint32_t>{1234, 5, 0x00020001, 11, 22, 7, 0, 0, 0, 9500}));
  }
  b.stop();
  // The frames the server answered for one read of the group are the frames planned.
  const uint64_t before = server->status().requests;
  const uint64_t sent = b.frames_sent();
  EXPECT_EQ(b.read(A("D0"), 2), (std::vector<uint32_t>{1234, 5}));
  EXPECT_EQ(b.frames_sent() - sent, 2u);
  EXPECT_EQ(server->status().requests - before, 2u);
  EXPECT_EQ(b.read(A("X0"), 16), plc.read(A("X0"), 16));
  EXPECT_EQ(b.frames_sent() - sent, 3u);  // 16 inputs: one frame
  EXPECT_EQ(b.status().errors, 0u) << b.status().last_error;
}

TEST(TriBridge, WritesForcingAndRunModeReachTheCell) {
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "t.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));  // a TRi runs unless halted
  auto server = serve(plc, 0);
  Collector c;
  Bridge b(link_to(server->port(), yaml("signals: {lamp: Y5}\n")), c.sinks());
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && c.io.back().ok; }));

  b.write(A("D99"), {4321});                 // DM[100]
  b.write(b.resolve("DM[101]"), {7});
  b.write(A("DR3762"), {123456});            // B
  b.write(A("M9"), {1});                     // relay 10: wb
  b.write(A("WM16"), {0xA5A5});              // RELAY[2]: one WVS
  b.write(b.resolve("TIMERSV[1]"), {150});
  b.write(b.resolve("PWM[1]"), {2500});     // WVS 0D 01
  b.write(A("F10"), {1, 2, 3});              // EEPROM[11..13]: one WXI
  b.write(A("X4"), {1});                     // plays the sensor
  EXPECT_EQ(plc.read(A("D99"), 2), (std::vector<uint32_t>{4321, 7}));
  EXPECT_EQ(plc.read(A("DR3762"), 1)[0], 123456u);
  EXPECT_EQ(plc.read(A("M9"), 1)[0], 1u);
  EXPECT_EQ(plc.read(A("WM16"), 1)[0], 0xA5A5u);
  EXPECT_EQ(plc.read(A("R3600"), 1)[0], 150u);
  EXPECT_EQ(plc.read(A("R3812"), 1)[0], 2500u);
  EXPECT_EQ(plc.read(A("F10"), 3), (std::vector<uint32_t>{1, 2, 3}));
  EXPECT_EQ(b.read(A("DR3762"), 1)[0], 123456u);
  EXPECT_THROW(b.write(A("R3762"), {1}), Error);  // half of B: refused before the link
  EXPECT_THROW(b.write(A("R3840"), {1}), Error);  // an ADC is an input
  EXPECT_THROW(b.write(A("R3600"), {10000}), Error);
  EXPECT_THROW(b.read(A("D4000"), 1), Error);

  // Forcing: written now and at every I/O poll until released.
  b.force(A("Y5"), true);
  EXPECT_EQ(plc.read(A("Y5"), 1)[0], 1u);
  plc.write(A("Y5"), {0});  // the program (or anyone) turns it off: the next poll sets it again
  c.clear();
  ASSERT_TRUE(c.wait([&] { return c.io.size() >= 2 && c.io.back().ok && c.io.back().signals[0]; }));
  EXPECT_EQ(plc.read(A("Y5"), 1)[0], 1u);
  ASSERT_EQ(b.forced().size(), 1u);
  EXPECT_EQ(b.release(nullptr), (std::vector<Address>{A("Y5")}));
  EXPECT_TRUE(b.forced().empty());
  const Address y5 = A("Y5");
  EXPECT_TRUE(b.release(&y5).empty());
  EXPECT_THROW(b.force(A("D0"), true), Error);

  b.set_run(false);  // C2: halted
  EXPECT_NE(plc.mode(), RunMode::Run);
  c.clear();
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && c.io.back().ok && !c.io.back().run; }));
  b.set_run(true);  // C3: resumed
  EXPECT_EQ(plc.mode(), RunMode::Run);
  c.clear();
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && c.io.back().ok && c.io.back().run; }));
  EXPECT_EQ(b.status().errors, 0u) << b.status().last_error;
  b.stop();
}

TEST(TriBridge, ReconnectsWhenTheServerComesBack) {
  Plc plc;
  plc.write(A("D0"), {1});
  auto server = serve(plc, 0);
  const int port = server->port();
  Collector c;
  Bridge b(link_to(port, yaml("groups: [{name: g, rate: 100, points: [\"DM[1]\"]}]")), c.sinks());
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok; }));

  server.reset();  // gone: the poll fails, the link drops, connection attempts fail
  ASSERT_TRUE(c.wait([&] { return c.errors.size() >= 3; })) << "no failed reconnection";
  EXPECT_FALSE(b.status().connected);
  EXPECT_THROW(b.read(A("D0"), 1), CommError);

  plc.write(A("D0"), {2});
  server = serve(plc, port);  // back, on the same port
  c.clear();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok && c.groups.back().values[0] == 2; }));
  EXPECT_TRUE(b.status().connected);
  EXPECT_EQ(b.status().reconnects, 2u);

  b.recover();
  EXPECT_EQ(b.status().last_error, "");
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && c.io.back().ok && b.status().reconnects == 3; }));
  b.stop();
}

TEST(TriBridge, AnotherIdIsNotConnected) {
  Plc plc;
  auto server = serve(plc, 0);
  BridgeConfig cfg = link_to(server->port(), {});
  cfg.id = 2;  // the server is 01: it stays silent
  cfg.timeout_s = 0.1;
  Collector c;
  Bridge b(cfg, c.sinks());
  EXPECT_NE(b.describe().find("ID 02"), std::string::npos) << b.describe();
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.errors.empty(); }));
  EXPECT_NE(c.errors.front().find("connect: "), std::string::npos) << c.errors.front();
  EXPECT_NE(c.errors.front().find("no answer to IR"), std::string::npos) << c.errors.front();
  EXPECT_FALSE(b.status().connected);
  b.stop();
}

TEST(TriBridge, PollsOverASerialLine) {
  fatek_test::TempDir dir;
  fatek_test::PtyPair pty(dir.path);
  Plc plc;
  plc.write(A("D6"), {42});
  ServerOptions so;
  so.id = 3;
  SerialServer server(plc, parse_serial_settings(pty.a + ":38400:8N1", "8N1"), so);
  server.start();
  BridgeConfig cfg = yaml("groups: [{name: g, rate: 50, points: [\"DM[7]\"]}]");
  cfg.serial = pty.b;  // 38400 8N1 by default
  cfg.id = 3;
  cfg.timeout_s = 3;
  cfg.io_rate_hz = 50;
  Collector c;
  Bridge b(cfg, c.sinks());
  EXPECT_EQ(b.describe(), "serial " + pty.b + ":38400:8N1 ID 03");
  b.start();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok; })) << b.status().last_error;
  EXPECT_EQ(c.groups.back().values, (std::vector<uint32_t>{42}));
  b.write(A("D6"), {43});
  ASSERT_TRUE(c.wait([&] { return c.groups.back().ok && c.groups.back().values[0] == 43; }));
  EXPECT_TRUE(b.status().connected);
  b.stop();
  server.stop();
}

// examples/tri/conveyor.yaml, tri_bridge.launch's default, names the demo cell's signals as
// the cell YAML does (so /tri_bridge/signals/<name> are /plc_node/signals/<name>), and its
// groups poll what the demo's program keeps: parts done (counter 1) and the pick and
// release timers (T50, T51).
TEST(TriBridge, ExampleConfigNamesTheDemoCellsSignals) {
  const BridgeConfig cfg = load_bridge_config(std::string(PLC_CELL_SOURCE_DIR) + "/examples/tri/conveyor.yaml");
  const YAML::Node cell = YAML::LoadFile(std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.yaml");
  std::vector<std::pair<std::string, Address>> demo;
  for (const auto& kv : cell["signals"]) demo.emplace_back(kv.first.as<std::string>(), A(kv.second.as<std::string>().c_str()));
  EXPECT_EQ(cfg.signals, demo);

  Plc plc;
  plc.locked([](ScanEngine&, Memory& m) {
    m.set_bit(Area::X, 3, true);  // part_present
    m.set_bit(Area::M, 0, true);  // line_running
    m.set_reg(Area::RC, 0, 7);    // 7 parts done
    m.set_reg(Area::RT, 50, 12);  // picking for 1.2 s
    for (uint16_t i = 0; i < 4; ++i) m.set_reg(Area::D, i, uint16_t(100 + i));
    return 0;
  });
  auto server = serve(plc, 0);
  Collector c;
  Bridge b(link_to(server->port(), cfg), c.sinks());
  b.start();
  const auto both_groups = [&] {
    bool seen[2] = {false, false};
    for (const GroupResult& g : c.groups) seen[g.group] = true;
    return seen[0] && seen[1];
  };
  ASSERT_TRUE(c.wait([&] { return !c.io.empty() && both_groups(); }));
  b.stop();
  const IoResult io = c.io.front();
  ASSERT_TRUE(io.ok) << io.error;
  // start_button, stop_button, part_present, stopper_down, conveyor_run, stopper_lower,
  // pick_request, line_running
  EXPECT_EQ(io.signals, (std::vector<bool>{false, false, true, false, false, false, false, true}));
  std::map<std::string, std::vector<uint32_t>> groups;
  for (const GroupResult& g : c.groups) {
    ASSERT_TRUE(g.ok) << g.error;
    groups[cfg.groups[g.group].name] = g.values;
  }
  EXPECT_EQ(groups["parts"], (std::vector<uint32_t>{7, 12, 0}));
  EXPECT_EQ(groups["recipe"], (std::vector<uint32_t>{100, 101, 102, 103}));
}
