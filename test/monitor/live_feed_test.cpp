// The monitor's WebSocket (/api/live): subscriptions, frames against the PLC's values after
// scans the test drives, status, log and program events, and its limits.
#include "monitor_fixture.h"

namespace plc_cell {
namespace monitor_test {
namespace {

TEST_F(MonitorTest, FramesCarryTheSubscribedValuesAfterEachScan) {
  serve();
  WsClient page(port);
  page.send(R"({"subscribe":{"networks":[0,1],"watch":["R0","Y0","D7"],"rate_hz":50}})");
  auto f = frame_at(page, 0);
  ASSERT_FALSE(f.is_null());
  EXPECT_EQ(f["values"]["Y0"], 0);
  EXPECT_EQ(f["values"]["R0"], 0);
  ASSERT_EQ(f["flow"].size(), 2u);
  EXPECT_EQ(f["flow"][1]["net"], 1);
  EXPECT_TRUE(f["values"].contains("X0"));  // network 0's contacts come with the frame
  const size_t dark = f["flow"][0]["on"].size();

  plc.set_input(0, true);
  scan();
  plc.write(parse_address("D7"), {1234});
  f = frame_at(page, 1);
  ASSERT_FALSE(f.is_null());
  EXPECT_EQ(f["scan"], 1);
  EXPECT_EQ(f["t_us"], 1000);
  EXPECT_EQ(f["mode"], "run");
  EXPECT_EQ(f["values"]["Y0"], 1);
  EXPECT_EQ(f["values"]["R0"], 7);
  EXPECT_EQ(f["values"]["X0"], 1);
  EXPECT_EQ(f["values"]["D7"], 1234);
  // The latch conducts now: more of network 0 carries power, its coil among it.
  EXPECT_GT(f["flow"][0]["on"].size(), dark);
}

TEST_F(MonitorTest, StatusComesWithoutAsking) {
  serve();
  scan();
  WsClient page(port);
  const auto s = page.next("status");
  ASSERT_FALSE(s.is_null());
  EXPECT_EQ(s["mode"], "run");
  EXPECT_EQ(s["scan"]["scans"], 1);
}

TEST_F(MonitorTest, EveryWriteIsLoggedToEveryPage) {
  settings.writable = WritableRanges::parse("D0-D9");
  serve();
  WsClient a(port), b(port);
  a.next("status");
  b.next("status");
  const auto t = token();
  http_post(port, "/api/write", R"({"address":"D1","values":[5]})", t);
  http_post(port, "/api/write", R"({"address":"D50","values":[6]})", t);
  for (WsClient* page : {&a, &b}) {
    auto l = page->next("log");
    ASSERT_FALSE(l.is_null());
    EXPECT_EQ(l["text"], "write D1 = 5 (accepted)");
    l = page->next("log");
    ASSERT_FALSE(l.is_null());
    EXPECT_EQ(l["text"], "write D50 = 6 (refused: D50 is not writable (writable: D0-D9))");
  }
}

TEST_F(MonitorTest, AChangeRefusedForItsFormIsLoggedOnceOnTheCellsClock) {
  settings.writable = WritableRanges::parse("D0-D9");
  serve();
  for (int i = 0; i < 7; ++i) scan();
  WsClient page(port);
  page.next("status");
  const auto t = token();
  EXPECT_EQ(http_post(port, "/api/write", R"({"address":"D1","values":[70000]})", t).status, 400);
  EXPECT_EQ(http_post(port, "/api/force", R"({"address":"D1","action":"on"})", t).status, 400);
  EXPECT_EQ(http_post(port, "/api/mode", R"({"mode":"pause"})", t).status, 400);
  EXPECT_EQ(http_post(port, "/api/write", R"({"address":"D1","values":[3]})", t).status, 200);
  const char* expected[] = {"write D1 (refused: ", "force D1 (refused: force: D1 is not a single discrete)",
                            "mode pause (refused: mode: \"mode\" must be run or stop, not 'pause')",
                            "write D1 = 3 (accepted)"};
  for (const char* text : expected) {
    const auto l = page.next("log");
    ASSERT_FALSE(l.is_null()) << text;
    EXPECT_EQ(l["text"].get<std::string>().rfind(text, 0), 0u) << l.dump();
    EXPECT_EQ(l["t_us"], 7000) << l.dump();  // the cell's clock: 7 scans of 1 ms
  }
  EXPECT_TRUE(page.next("log", std::chrono::milliseconds(300)).is_null());  // each once
}

TEST_F(MonitorTest, AProgramChangeIsAnnounced) {
  serve();
  WsClient page(port);
  page.next("status");
  plc.load_program_text("ORG X2\nOUT Y3\nEND\n", "other.il");
  const auto p = page.next("program");
  ASSERT_FALSE(p.is_null());
  EXPECT_EQ(p["version"], 2);
  const auto ladder = http_get(port, "/api/ladder").json();
  EXPECT_EQ(ladder["file"], "other.il");
  EXPECT_EQ(ladder["version"], 2);
}

TEST_F(MonitorTest, BadSubscriptionsAreAnsweredWithAnErrorNamingTheField) {
  serve();
  WsClient page(port);
  std::string big = R"({"subscribe":{"watch":[)";
  for (int i = 0; i < 513; ++i) big += std::string(i ? "," : "") + "\"D" + std::to_string(i) + "\"";
  big += "]}}";
  const std::pair<std::string, std::string> cases[] = {
      {"not json", "not JSON"},
      {R"({"subscribe":{"rate_hz":0}})", "rate_hz"},
      {R"({"subscribe":{"rate_hz":51}})", "rate_hz"},
      {R"({"subscribe":{"networks":[9]}})", "networks"},
      {R"({"subscribe":{"watch":["nothing_here"]}})", "nothing_here"},
      {R"({"subscribe":{"colour":1}})", "colour"},
      {big, "the limit is 512"},
  };
  for (const auto& [msg, why] : cases) {
    page.send(msg);
    const auto e = page.next("error");
    ASSERT_FALSE(e.is_null()) << msg;
    EXPECT_NE(e["error"].get<std::string>().find(why), std::string::npos) << e.dump();
  }
  // Still served.
  page.send(R"({"subscribe":{"watch":["R0"]}})");
  EXPECT_FALSE(page.next("frame").is_null());
}

TEST_F(MonitorTest, WebSocketFromAForeignOriginOrHostIsRefused) {
  serve();
  const std::string self = "127.0.0.1:" + std::to_string(port);
  EXPECT_EQ(ws_upgrade(port, self, "http://evil.example"), 403);
  EXPECT_EQ(ws_upgrade(port, "evil.example:" + std::to_string(port), "http://evil.example:" + std::to_string(port)), 403);
  EXPECT_EQ(ws_upgrade(port, self, "http://" + self, "/elsewhere"), 404);
  EXPECT_EQ(ws_upgrade(port, self, "http://" + self), 101);
}

TEST_F(MonitorTest, ASubscribedPageIsNotIdle) {
  settings.idle_timeout_us = 200'000;
  serve();
  WsClient page(port);
  page.send(R"({"subscribe":{"watch":["R0"],"rate_hz":20}})");
  // Frames keep coming well past the idle timeout.
  for (int i = 0; i < 15; ++i) ASSERT_FALSE(page.next("frame").is_null()) << i;
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
