// The monitor's HTTP API against a real server (docs/monitor-api.md).
#include "monitor_fixture.h"

namespace plc_cell {
namespace monitor_test {
namespace {

uint32_t value(Plc& plc, const char* a) { return plc.read(parse_address(a), 1)[0]; }

TEST_F(MonitorTest, SessionGivesTokenWritableRangesAndKind) {
  settings.writable = WritableRanges::parse("D0-D99,M800");
  serve();
  const auto r = http_get(port, "/api/session");
  ASSERT_EQ(r.status, 200);
  const auto j = r.json();
  EXPECT_EQ(j["token"], server->token());
  EXPECT_EQ(j["token"].get<std::string>().size(), 32u);
  EXPECT_EQ(j["writable"], "D0-D99,M800");
  EXPECT_EQ(j["source"], "cell test");
  EXPECT_EQ(j["kind"], "live");
  EXPECT_EQ(j["rate_hz"], 10);
}

TEST_F(MonitorTest, ReadGivesTheValuesOfOneInstant) {
  serve();
  plc.set_input(0, true);
  scan();
  scan();
  const auto r = http_get(port, "/api/read?a=X0,Y0,R0,X1");
  ASSERT_EQ(r.status, 200) << r.body;
  const auto j = r.json();
  EXPECT_EQ(j["values"]["X0"], 1);
  EXPECT_EQ(j["values"]["Y0"], 1);
  EXPECT_EQ(j["values"]["R0"], 7);
  EXPECT_EQ(j["values"]["X1"], 0);
  EXPECT_EQ(j["scan"], 2);
  EXPECT_EQ(j["t_us"], 2000);
  EXPECT_EQ(j["mode"], "run");
}

TEST_F(MonitorTest, ReadOfAnUnknownNameIs400NamingIt) {
  serve();
  const auto r = http_get(port, "/api/read?a=R0,no_such_thing");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.json().value("error", "").find("no_such_thing"), std::string::npos) << r.body;
  EXPECT_EQ(http_get(port, "/api/read").status, 400);
  EXPECT_EQ(http_get(port, "/api/read?a=R%zz").status, 400);
}

TEST_F(MonitorTest, LadderListsTheNetworks) {
  serve();
  const auto r = http_get(port, "/api/ladder");
  ASSERT_EQ(r.status, 200);
  const auto j = r.json();
  EXPECT_EQ(j["file"], "belt.il");
  EXPECT_EQ(j["version"], 1);
  ASSERT_EQ(j["networks"].size(), 3u);  // the latch, the move, END
  EXPECT_EQ(j["networks"][0]["number"], 1);
  EXPECT_EQ(j["networks"][1]["number"], 2);
  EXPECT_TRUE(j["networks"][2]["number"].is_null());  // END is no network
  EXPECT_EQ(j["networks"][0]["line"], 1);
  EXPECT_EQ(j["networks"][1]["line"], 5);
  EXPECT_EQ(j["networks"][2]["line"], 7);
  EXPECT_TRUE(j["networks"][0]["drawable"]);
  EXPECT_EQ(j["networks"][0]["elements"][0]["address"], "X0");
}

TEST_F(MonitorTest, StatusReportsModeScansAndForcedPoints) {
  config.signals = {{"stop_pb", parse_address("X1")}};
  serve();
  plc.force(parse_address("X1"), ForceAction::Disable);
  plc.force(parse_address("X1"), ForceAction::Set);
  plc.force(parse_address("Y3"), ForceAction::Disable);  // held in the state it had: off
  for (int i = 0; i < 3; ++i) scan();
  const auto r = http_get(port, "/api/status");
  ASSERT_EQ(r.status, 200);
  const auto j = r.json();
  EXPECT_EQ(j["mode"], "run");
  EXPECT_EQ(j["scan"]["scans"], 3);
  EXPECT_EQ(j["scan"]["overruns_off_cpu"], 0);  // virtual scans: none missed, none off the CPU
  // Virtual scans are not timed: no cycle figures rather than 0 µs.
  EXPECT_TRUE(j["scan"]["cycle_avg_ns"].is_null()) << j["scan"].dump();
  EXPECT_TRUE(j["scan"]["cycle_max_ns"].is_null()) << j["scan"].dump();
  EXPECT_EQ(j["scan_note"], "");
  // Each forced point with the cell's name for it and the state it is held in.
  ASSERT_EQ(j["forced"].size(), 2u) << j["forced"].dump();
  EXPECT_EQ(j["forced"][0], nlohmann::json({{"address", "X1"}, {"name", "stop_pb"}, {"state", 1}}));
  EXPECT_EQ(j["forced"][1], nlohmann::json({{"address", "Y3"}, {"name", ""}, {"state", 0}}));
  EXPECT_FALSE(j["mode_switchable"]);  // read-only server
}

TEST_F(MonitorTest, WriteWithinTheRangesChangesThePlc) {
  settings.writable = WritableRanges::parse("D0-D99,M800");
  serve();
  const auto r = http_post(port, "/api/write", R"({"address":"D5","values":[42,-1]})", token());
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(value(plc, "D5"), 42u);
  EXPECT_EQ(value(plc, "D6"), 0xFFFFu);
}

TEST_F(MonitorTest, WriteOutsideTheRangesIsRefusedAndChangesNothing) {
  settings.writable = WritableRanges::parse("D0-D99,M800");
  serve();
  const auto t = token();
  auto r = http_post(port, "/api/write", R"({"address":"D500","values":[5]})", t);
  EXPECT_EQ(r.status, 403);
  EXPECT_EQ(r.json()["error"], "write D500 = 5: D500 is not writable (writable: D0-D99,M800)");
  // Straddling the end of a range is refused whole.
  r = http_post(port, "/api/write", R"({"address":"D99","values":[1,2]})", t);
  EXPECT_EQ(r.status, 403);
  EXPECT_EQ(value(plc, "D500"), 0u);
  EXPECT_EQ(value(plc, "D99"), 0u);
}

TEST_F(MonitorTest, ReadOnlyByDefault) {
  serve();
  const auto r = http_post(port, "/api/write", R"({"address":"D0","values":[5]})", token());
  EXPECT_EQ(r.status, 403);
  EXPECT_NE(r.json().value("error", "").find("writable: none"), std::string::npos) << r.body;
  EXPECT_EQ(value(plc, "D0"), 0u);
}

TEST_F(MonitorTest, WriteWithoutOrWithAWrongTokenIsRefused) {
  settings.writable = WritableRanges::parse("all");
  serve();
  auto r = http_post(port, "/api/write", R"({"address":"D0","values":[5]})", "");
  EXPECT_EQ(r.status, 403);
  EXPECT_NE(r.json().value("error", "").find("X-Plc-Token"), std::string::npos) << r.body;
  r = http_post(port, "/api/write", R"({"address":"D0","values":[5]})", std::string(32, '0'));
  EXPECT_EQ(r.status, 403);
  r = http_post(port, "/api/mode", R"({"mode":"stop"})", "nope");
  EXPECT_EQ(r.status, 403);
  EXPECT_EQ(value(plc, "D0"), 0u);
  EXPECT_EQ(plc.mode(), RunMode::Run);
}

TEST_F(MonitorTest, ForeignOriginAndHostAreRefused) {
  settings.writable = WritableRanges::parse("all");
  serve();
  const std::string t = token();
  HttpCall c;
  c.method = "POST";
  c.target = "/api/write";
  c.body = R"({"address":"D0","values":[5]})";
  c.token = t;
  c.origin = "http://evil.example";
  auto r = http_call(port, c);
  EXPECT_EQ(r.status, 403);
  EXPECT_NE(r.json().value("error", "").find("Origin"), std::string::npos) << r.body;
  // DNS rebinding: the attacker's name resolves to 127.0.0.1, same-origin for the browser.
  c.host = "evil.example:" + std::to_string(port);
  c.origin = "http://" + c.host;
  r = http_call(port, c);
  EXPECT_EQ(r.status, 403);
  EXPECT_NE(r.json().value("error", "").find("Host"), std::string::npos) << r.body;
  c = {};
  c.target = "/api/session";
  c.host = "evil.example";
  EXPECT_EQ(http_call(port, c).status, 403);
  EXPECT_EQ(value(plc, "D0"), 0u);
  // Same-origin through a tunnel's other port, and localhost, are this server.
  c.host = "localhost:9999";
  c.origin = "http://localhost:9999";
  EXPECT_EQ(http_call(port, c).status, 200);
}

TEST_F(MonitorTest, AllowedHostsAreAccepted) {
  settings.allowed_hosts = {"plc.lan"};
  serve();
  HttpCall c;
  c.target = "/api/session";
  c.host = "PLC.lan:8080";
  EXPECT_EQ(http_call(port, c).status, 200);
}

TEST_F(MonitorTest, ForceOffAndReleaseWithinTheRanges) {
  settings.writable = WritableRanges::parse("M800,Y0");
  serve();
  const auto t = token();
  plc.set_input(0, true);  // the latch would turn Y0 on
  ASSERT_EQ(http_post(port, "/api/force", R"({"address":"Y0","action":"off"})", t).status, 200);
  scan();
  EXPECT_EQ(value(plc, "Y0"), 0u);  // forced: the program's OUT leaves it
  EXPECT_EQ(http_get(port, "/api/status").json()["forced"][0]["address"], "Y0");
  ASSERT_EQ(http_post(port, "/api/force", R"({"address":"Y0","action":"release"})", t).status, 200);
  scan();
  EXPECT_EQ(value(plc, "Y0"), 1u);
  EXPECT_EQ(http_get(port, "/api/status").json()["forced"].size(), 0u);
  EXPECT_EQ(http_post(port, "/api/force", R"({"address":"Y1","action":"on"})", t).status, 403);
  EXPECT_EQ(http_post(port, "/api/force", R"({"address":"Y0","action":"maybe"})", t).status, 400);
  EXPECT_EQ(http_post(port, "/api/force", R"({"address":"R0","action":"on"})", t).status, 400);
}

TEST_F(MonitorTest, AccessSaysBeforeAnyClickWhatTheServerWouldRefuse) {
  settings.writable = WritableRanges::parse("D0-D99,X0-X7");
  config.signals = {{"start_pb", parse_address("X0")}};
  serve();
  const auto j = http_get(port, "/api/access?a=D5,D100,DD98,DD99,X3,start_pb,Y0,R0").json();
  const std::string none = "", ranges = " is not writable (writable: D0-D99,X0-X7)";
  const std::map<std::string, std::pair<std::string, std::string>> expected = {
      {"D5", {none, "D5 is not a single discrete"}},
      {"D100", {"D100" + ranges, "D100 is not a single discrete"}},
      {"DD98", {none, "DD98 is not a single discrete"}},
      {"DD99", {"DD99" + ranges, "DD99 is not a single discrete"}},  // D99 and D100
      {"X3", {none, none}},
      {"start_pb", {none, none}},
      {"Y0", {"Y0" + ranges, "Y0" + ranges}},
      {"R0", {"R0" + ranges, "R0 is not a single discrete"}}};
  ASSERT_EQ(j.size(), expected.size()) << j.dump();
  for (const auto& [name, why] : expected) {
    EXPECT_EQ(j[name]["write"], why.first) << name;
    EXPECT_EQ(j[name]["force"], why.second) << name;
  }
  // What it says is what a POST then does.
  const auto t = token();
  EXPECT_EQ(http_post(port, "/api/write", R"({"address":"DD98","values":[5]})", t).status, 200);
  EXPECT_EQ(http_post(port, "/api/write", R"({"address":"DD99","values":[5]})", t).status, 403);
  EXPECT_EQ(http_post(port, "/api/force", R"({"address":"start_pb","action":"on"})", t).status, 200);
  EXPECT_EQ(http_get(port, "/api/access").status, 400);
  EXPECT_EQ(http_get(port, "/api/access?a=no_such").status, 400);
  // RUN/STOP: its reason in the status.
  EXPECT_EQ(http_get(port, "/api/status").json()["mode_refusal"],
            "RUN/STOP needs writable: all (writable: D0-D99,X0-X7)");
}

TEST_F(MonitorTest, AReadOnlyServerSaysWhyEveryControlIsOff) {
  serve();
  const auto j = http_get(port, "/api/access?a=D0,X0").json();
  EXPECT_EQ(j["D0"]["write"], "D0 is not writable (writable: none)");
  EXPECT_EQ(j["X0"]["force"], "X0 is not writable (writable: none)");
  const auto s = http_get(port, "/api/status").json();
  EXPECT_FALSE(s["mode_switchable"]);
  EXPECT_EQ(s["mode_refusal"], "RUN/STOP needs writable: all (writable: none)");
}

TEST_F(MonitorTest, ModeNeedsWritableAll) {
  settings.writable = WritableRanges::parse("D0-D9");
  serve();
  EXPECT_EQ(http_post(port, "/api/mode", R"({"mode":"stop"})", token()).status, 403);
  EXPECT_EQ(plc.mode(), RunMode::Run);
  server->stop();
  settings.writable = WritableRanges::parse("all");
  serve();
  EXPECT_EQ(http_post(port, "/api/mode", R"({"mode":"stop"})", token()).status, 200);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_TRUE(http_get(port, "/api/status").json()["mode_switchable"]);
  EXPECT_EQ(http_get(port, "/api/status").json()["mode_refusal"], "");
}

TEST_F(MonitorTest, CoverageIsRecordedOnceAsked) {
  serve();
  auto j = http_get(port, "/api/coverage").json();
  ASSERT_TRUE(j["available"]);
  ASSERT_EQ(j["seen"].size(), 7u);
  EXPECT_EQ(j["seen"][0], 0);  // nothing scanned since it started
  scan();
  j = http_get(port, "/api/coverage").json();
  EXPECT_EQ(j["seen"][0], 1);  // ORG X0 saw X0 off
}

TEST_F(MonitorTest, ReplayIsNotFoundOnALiveCell) {
  serve();
  EXPECT_EQ(http_get(port, "/api/replay").status, 404);
  EXPECT_EQ(http_post(port, "/api/replay", R"({"seek_us":0})", token()).status, 404);
  EXPECT_EQ(http_get(port, "/api/nothing").status, 404);
}

TEST_F(MonitorTest, StaticFilesComeFromTheAssetRootAndNeverLeaveIt) {
  serve();
  auto r = http_get(port, "/");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, "<html>monitor</html>");
  EXPECT_EQ(r.content_type, "text/html; charset=utf-8");
  r = http_get(port, "/assets/js/app.js");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.body, "let x = 1;");
  for (const char* bad : {"/assets/../index.html", "/assets/js/../../../etc/passwd", "/assets/%2e%2e/x", "/vendor/../x"}) {
    r = http_get(port, bad);
    EXPECT_EQ(r.status, 400) << bad;
    EXPECT_TRUE(r.json().contains("error")) << bad;
  }
  EXPECT_EQ(http_get(port, "/assets/none.js").status, 404);
  // libjs-dygraphs is one of the package's dependencies.
  r = http_get(port, "/vendor/dygraphs/dygraph.min.js");
  EXPECT_EQ(r.status, 200);
  EXPECT_EQ(r.content_type, "text/javascript; charset=utf-8");
}

TEST_F(MonitorTest, BodyOverTheLimitIs413) {
  settings.writable = WritableRanges::parse("all");
  serve();
  const std::string big = R"({"address":"D0","values":[)" + std::string(70000, ' ') + "1]}";
  const auto r = http_post(port, "/api/write", big, token());
  EXPECT_EQ(r.status, 413);
  EXPECT_NE(r.json().value("error", "").find("65536"), std::string::npos) << r.body;
  EXPECT_EQ(value(plc, "D0"), 0u);
}

TEST_F(MonitorTest, MalformedBodiesAre400) {
  settings.writable = WritableRanges::parse("all");
  serve();
  const auto t = token();
  for (const char* body : {"", "{", "[1]", R"({"address":5,"values":[1]})", R"({"address":"D0"})",
                           R"({"address":"D0","values":[]})", R"({"address":"D0","values":["x"]})",
                           R"({"address":"D0","values":[70000]})", R"({"address":"Q0","values":[1]})"}) {
    const auto r = http_post(port, "/api/write", body, t);
    EXPECT_EQ(r.status, 400) << body;
    EXPECT_TRUE(r.json().contains("error")) << body << " -> " << r.body;
  }
  EXPECT_EQ(value(plc, "D0"), 0u);
}

TEST_F(MonitorTest, ConnectionsOverTheCapAreRefusedWhenEveryOneIsBusy) {
  settings.max_connections = 2;
  serve();
  // Two pages receiving frames: neither gives up its slot.
  WsClient a(port), b(port);
  for (WsClient* p : {&a, &b}) {
    p->send(R"({"subscribe":{"watch":["R0"],"rate_hz":20}})");
    ASSERT_FALSE(p->next("frame").is_null());
  }
  const auto r = http_get(port, "/api/session");
  EXPECT_EQ(r.status, 503);
  EXPECT_NE(r.json().value("error", "").find("max_connections 2"), std::string::npos) << r.body;
  EXPECT_GE(server->status().rejected, 1u);
  for (WsClient* p : {&a, &b}) EXPECT_FALSE(p->next("frame").is_null());
}

TEST_F(MonitorTest, SilentConnectionsAreClosedAfterTheIdleTimeout) {
  settings.idle_timeout_us = 200'000;
  serve();
  EXPECT_TRUE(closed_when_silent(port, std::chrono::milliseconds(3000)));
  WsClient page(port);  // a page that never subscribes is idle too
  EXPECT_TRUE(page.closed_within(std::chrono::milliseconds(3000)));
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
