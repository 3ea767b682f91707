// What a frame says besides the values: no power flow while no network runs (STOP), and
// which of its points are forced (docs/monitor-api.md, "WebSocket /api/live").
#include <set>

#include "monitor_fixture.h"
#include "plc_cell/coverage/report.h"

namespace plc_cell {
namespace monitor_test {
namespace {

TEST_F(MonitorTest, InStopNoNetworkCarriesPowerAndTheValuesAreAsTheyAre) {
  serve();
  WsClient page(port);
  page.send(R"({"subscribe":{"networks":[0,1],"watch":["Y0"],"rate_hz":50}})");
  plc.set_input(0, true);
  scan();
  auto f = frame_at(page, 1);
  ASSERT_FALSE(f.is_null());
  ASSERT_EQ(f["values"]["Y0"], 1);  // latched
  ASSERT_GT(energised(f), 0u);
  EXPECT_FALSE(f.contains("no_flow")) << f.dump();
  plc.set_mode(RunMode::Stop);
  // Frames sent before the switch may still be on their way.
  for (int i = 0; i < 100 && f["mode"] != "stop"; ++i) f = page.next("frame");
  ASSERT_EQ(f["mode"], "stop");
  // The frames after STOP: the outputs are off (Y0 = 0: network 1's contact open) while X0 is
  // still on. No network runs, so none is drawn energised: the coil of Y0 drawn on from X0
  // beside its own contact drawn open would be a lie.
  for (int i = 0; i < 3; ++i, f = page.next("frame")) {
    ASSERT_FALSE(f.is_null());
    EXPECT_EQ(f["mode"], "stop");
    EXPECT_EQ(f["values"]["Y0"], 0);
    EXPECT_EQ(f["values"]["X0"], 1);
    ASSERT_EQ(f["flow"].size(), 2u);
    EXPECT_EQ(energised(f), 0u) << f["flow"].dump();
    ASSERT_TRUE(f["no_flow"].is_string()) << f.dump();
    EXPECT_NE(f["no_flow"].get<std::string>().find("STOP"), std::string::npos);
  }
  plc.set_mode(RunMode::Run);
  scan();
  f = frame_at(page, 2);
  ASSERT_FALSE(f.is_null());
  EXPECT_GT(energised(f), 0u);
}

TEST_F(MonitorTest, FramesMarkTheForcedPointsByTheirKeys) {
  config.signals = {{"stop_pb", parse_address("X1")}};
  serve();
  WsClient page(port);
  page.send(R"({"subscribe":{"networks":[0],"watch":["stop_pb","R0","Y0"],"rate_hz":50}})");
  ASSERT_FALSE(page.next("frame").is_null());
  plc.force(parse_address("X1"), ForceAction::Disable);
  plc.force(parse_address("X1"), ForceAction::Set);
  scan();
  const auto f = frame_at(page, 1);
  ASSERT_FALSE(f.is_null());
  // X1 as network 0 draws it and as the watch list names it; nothing else.
  std::set<std::string> forced;
  for (const auto& k : f["forced"]) forced.insert(k.get<std::string>());
  EXPECT_EQ(forced, (std::set<std::string>{"X1", "stop_pb"})) << f["forced"].dump();
  EXPECT_EQ(f["values"]["stop_pb"], 1);
  plc.force(parse_address("X1"), ForceAction::Enable);
  scan();
  EXPECT_TRUE(frame_at(page, 2)["forced"].empty());
}

TEST_F(MonitorTest, TheLadderNumbersNetworksFromOneAsCoverageDoes) {
  plc.load_program_text("ORG X0\nOUT Y0\nCALL SUB\nORG X1\nOUT Y1\nEND\nLBL SUB\nORG X2\nOUT Y2\nRTS\n", "sub.il");
  serve();
  const auto j = http_get(port, "/api/ladder").json();
  std::vector<nlohmann::json> numbers, lines;
  for (const auto& n : j["networks"]) {
    numbers.push_back(n["number"]);
    lines.push_back(n["line"]);
  }
  // The ORG networks 1, 2, 3 (the third in the routine); END, LBL and RTS are no network.
  EXPECT_EQ(numbers, (std::vector<nlohmann::json>{1, 2, nullptr, nullptr, 3, nullptr}));
  EXPECT_EQ(lines, (std::vector<nlohmann::json>{1, 4, 6, 7, 8, 10}));
  // The same numbers at the same lines as the coverage report's.
  const Program p = plc.locked([](const ScanEngine& se, const Memory&) { return se.program(); });
  std::vector<std::pair<uint32_t, int>> coverage, ladder;
  for (const auto& n : coverage::networks_of(p, std::vector<uint8_t>(p.code.size()),
                                             std::vector<std::string>(p.code.size()), {}))
    coverage.emplace_back(n.number, n.line);
  for (const auto& n : j["networks"])
    if (!n["number"].is_null()) ladder.emplace_back(n["number"].get<uint32_t>(), n["line"].get<int>());
  EXPECT_EQ(ladder, coverage);
}

TEST_F(MonitorTest, TheSourceSaysItsKind) {
  // A live cell that calls itself remote: the session says what the source says.
  struct Calling : monitor::LiveSource {
    using LiveSource::LiveSource;
    monitor::SourceKind kind() const override { return monitor::SourceKind::Remote; }
  };
  settings.endpoint = "127.0.0.1:0";
  settings.asset_root = assets_;
  Calling remote(ServerContext(plc), "cell test");
  monitor::HttpServer other(remote, settings);
  other.start();
  EXPECT_EQ(http_get(other.port(), "/api/session").json()["kind"], "remote");
  other.stop();
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
