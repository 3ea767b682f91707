// The monitor's API over a real PLC's host link (remote/remote_source.h), the soft PLC's own
// FATEK and TRi servers standing in for the PLC on loopback: what the pages are told about
// its scan figures, its forced points, and a link that goes and comes back
// (docs/monitor-remote.md).
#include "monitor_fixture.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/remote/fatek_link.h"
#include "plc_cell/remote/remote_source.h"
#include "plc_cell/remote/tri_link.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/tri/server.h"

namespace plc_cell {
namespace monitor_test {
namespace {

const std::string kConveyor = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.il";

class RemotePage : public ::testing::Test {
 protected:
  void SetUp() override {
    plc.load_program_file(kConveyor);
    serve_fatek(0);
    remote::FatekLinkOptions o;
    o.endpoint = "127.0.0.1:" + std::to_string(fatek->port());
    o.timeout_ms = 500;
    // No pause between retries of a down link: every poll asks the line again.
    source = std::make_unique<remote::RemoteSource>(std::make_unique<remote::FatekLink>(o),
                                                    remote::load_program_view(kConveyor, SoftCell::functions()),
                                                    std::chrono::milliseconds(0), std::chrono::hours(1));
    monitor::HttpSettings s;
    s.endpoint = "127.0.0.1:0";
    s.writable = WritableRanges::parse("all");
    http = std::make_unique<monitor::HttpServer>(*source, s);
    http->start();
    port = http->port();
  }
  void TearDown() override { http->stop(); }
  void serve_fatek(int at) {
    fatek::TcpServerOptions o;
    o.port = at;
    fatek = std::make_unique<fatek::TcpServer>(plc, o);
    fatek->start();
  }
  nlohmann::json status() { return http_get(port, "/api/status").json(); }
  nlohmann::json link() { return status()["servers"][0]; }

  Plc plc{SoftCell::functions()};
  std::unique_ptr<fatek::TcpServer> fatek;
  std::unique_ptr<remote::RemoteSource> source;
  std::unique_ptr<monitor::HttpServer> http;
  uint16_t port = 0;
};

TEST_F(RemotePage, NoPollFiguresPassForThePlcsScanFigures) {
  ASSERT_EQ(http_get(port, "/api/read?a=M0,D0").status, 200);
  const auto s = status();
  // The FATEK host link has no scan time: none is given, and it says so.
  EXPECT_TRUE(s["scan"].is_null()) << s["scan"].dump();
  EXPECT_EQ(s["scan_note"], remote::kRemoteScanNote);
  // The polls' own figures are there, under their own name.
  bool polling = false;
  for (const auto& e : s["extensions"])
    if (e["name"] == "polling") {
      polling = true;
      EXPECT_EQ(e["values"][0], nlohmann::json({"polls", "1"})) << e.dump();
    }
  EXPECT_TRUE(polling) << s["extensions"].dump();
  EXPECT_EQ(s["mode"], "stop");
}

TEST_F(RemotePage, ThePlcsForcedPointsAreReadFromIt) {
  // Forced in the PLC, not through this monitor.
  plc.force(parse_address("X3"), ForceAction::Disable);
  plc.force(parse_address("X3"), ForceAction::Set);
  plc.force(parse_address("M0"), ForceAction::Disable);
  WsClient page(port);
  page.send(R"({"subscribe":{"networks":[0,2],"watch":["X3"],"rate_hz":20}})");
  const auto f = page.next("frame");
  ASSERT_FALSE(f.is_null());
  std::set<std::string> marked;
  for (const auto& k : f["forced"]) marked.insert(k.get<std::string>());
  EXPECT_EQ(marked, (std::set<std::string>{"X3", "M0"})) << f.dump();
  const auto s = status();
  ASSERT_EQ(s["forced"].size(), 2u) << s.dump();
  EXPECT_EQ(s["forced"][0], nlohmann::json({{"address", "X3"}, {"name", ""}, {"state", 1}}));
  EXPECT_EQ(s["forced"][1], nlohmann::json({{"address", "M0"}, {"name", ""}, {"state", 0}}));
  EXPECT_NE(s["forced_note"].get<std::string>().find("read from the PLC"), std::string::npos) << s["forced_note"];
  // Released in the PLC: gone at the next reading (this source reads them again at once
  // only for points new to it; here every hour).
  plc.force(parse_address("X3"), ForceAction::Enable);
  EXPECT_EQ(status()["forced"].size(), 2u);
}

TEST_F(RemotePage, ALinkThatIsBackLeavesNoOldErrorAndTheModeIsKnownAgain) {
  ASSERT_EQ(http_get(port, "/api/read?a=D0").status, 200);
  EXPECT_EQ(status()["mode"], "stop");
  const int at = fatek->port();
  fatek.reset();  // the PLC goes away
  EXPECT_EQ(http_get(port, "/api/read?a=D0").status, 400);
  auto s = status();
  EXPECT_EQ(s["mode"], "unknown");  // not the last mode it reported
  EXPECT_FALSE(s["servers"][0]["link_up"]);
  EXPECT_NE(s["servers"][0]["last_error"].get<std::string>().find("read"), std::string::npos);
  serve_fatek(at);  // back on its address
  ASSERT_EQ(http_get(port, "/api/read?a=D0").status, 200);
  s = status();
  EXPECT_TRUE(s["servers"][0]["link_up"]);
  EXPECT_EQ(s["servers"][0]["last_error"], "");
  EXPECT_EQ(s["mode"], "stop");
}

TEST(RemoteTriPage, SaysItCannotForceBeforeAnyClick) {
  Plc plc{SoftCell::functions()};
  plc.load_program_file(kConveyor);
  tri::TcpServer tri(plc, "127.0.0.1", 0, {});
  tri.start();
  remote::TriLinkOptions o;
  o.endpoint = "127.0.0.1:" + std::to_string(tri.port());
  remote::RemoteSource source(std::make_unique<remote::TriLink>(o),
                              remote::load_program_view(kConveyor, SoftCell::functions()));
  monitor::HttpSettings s;
  s.endpoint = "127.0.0.1:0";
  s.writable = WritableRanges::parse("all");
  monitor::HttpServer http(source, s);
  http.start();
  ASSERT_EQ(http_get(http.port(), "/api/read?a=Y0").status, 200);
  const auto access = http_get(http.port(), "/api/access?a=Y0").json();
  EXPECT_EQ(access["Y0"]["write"], "");
  EXPECT_NE(access["Y0"]["force"].get<std::string>().find("no DISABLE flag"), std::string::npos) << access.dump();
  const auto st = http_get(http.port(), "/api/status").json();
  EXPECT_TRUE(st["forced"].empty());
  EXPECT_NE(st["forced_note"].get<std::string>().find("none can be"), std::string::npos) << st["forced_note"];
  http.stop();
}

TEST(RemoteTriPage, RunOrStopIsNotKnownUntilTheMonitorSwitchesIt) {
  Plc plc{SoftCell::functions()};
  plc.load_program_file(kConveyor);
  plc.set_mode(RunMode::Run);  // running, which nothing of the TRi's host link reports
  tri::TcpServer tri(plc, "127.0.0.1", 0, {});
  tri.start();
  remote::TriLinkOptions o;
  o.endpoint = "127.0.0.1:" + std::to_string(tri.port());
  remote::RemoteSource source(std::make_unique<remote::TriLink>(o),
                              remote::load_program_view(kConveyor, SoftCell::functions()));
  monitor::HttpSettings s;
  s.endpoint = "127.0.0.1:0";
  s.writable = WritableRanges::parse("all");
  monitor::HttpServer http(source, s);
  http.start();
  EXPECT_EQ(http_get(http.port(), "/api/read?a=Y0").json()["mode"], "unknown");
  EXPECT_EQ(http_get(http.port(), "/api/status").json()["mode"], "unknown");
  const std::string token = http_get(http.port(), "/api/session").json().value("token", "");
  ASSERT_EQ(http_post(http.port(), "/api/mode", R"({"mode": "stop"})", token).status, 200);  // C2, Halt
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_EQ(http_get(http.port(), "/api/read?a=Y0").json()["mode"], "stop");
  http.stop();
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
