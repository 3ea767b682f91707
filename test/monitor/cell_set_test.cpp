// One monitor for several cells (docs/monitor-api.md, "A line's cells"): each cell's API
// under /cell/NAME/, the overview at /api/overview, qualified names of another cell, and a
// request for a cell that is not there refused with the reason, changing nothing.
#include <random>

#include "monitor_fixture.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace monitor_test {
namespace {

class CellSetTest : public ::testing::Test {
 protected:
  void SetUp() override {
    for (Plc* p : {&a, &b}) {
      p->load_program_text(kProgram, "belt.il");
      p->set_mode(RunMode::Run);
    }
  }
  void TearDown() override {
    if (server) server->stop();
  }
  void serve(std::shared_ptr<const monitor::PropertyBoard> board = nullptr) {
    monitor::SourceSet set;
    set.watch(board);
    set.set_title("line test");
    set.add("a", std::make_unique<monitor::LiveSource>(ServerContext(a), "cell a"));
    set.add("b", std::make_unique<monitor::LiveSource>(ServerContext(b), "cell b"));
    set.add_wire({"a.Y0", "b.X0", "a.Y0 -> b.X0"});
    set.add_wire({"a.Y0", "c.X0", "a.Y0 -> c.X0"});  // a cell this monitor does not have
    settings.endpoint = "127.0.0.1:0";
    settings.writable = WritableRanges::parse("all");
    server = std::make_unique<monitor::HttpServer>(std::move(set), settings);
    server->start();
    port = server->port();
  }
  void scan_both() {
    t_us += 1000;
    a.scan(t_us);
    b.scan(t_us);
  }
  // Everything a request could change in either cell: modes, memory, forced points.
  std::string state() {
    std::string s;
    for (Plc* p : {&a, &b}) {
      s += p->mode() == RunMode::Run ? "R" : "S";
      for (const char* addr : {"X0", "X1", "Y0", "R0", "D0", "D1", "M0"})
        s += "," + std::to_string(p->read(parse_address(addr), 1)[0]);
      p->locked([&](ScanEngine&, Memory& m) {
        s += ",forced" + std::to_string(m.disabled_points().size());
        return 0;
      });
    }
    return s;
  }
  nlohmann::json overview() { return http_get(port, "/api/overview").json(); }

  Plc a, b;
  monitor::HttpSettings settings;
  std::unique_ptr<monitor::HttpServer> server;
  uint16_t port = 0;
  uint64_t t_us = 0;
};

TEST_F(CellSetTest, OverviewListsEachCellWithItsOwnMode) {
  serve();
  scan_both();
  auto o = overview();
  ASSERT_EQ(o["cells"].size(), 2u) << o.dump();
  EXPECT_EQ(o["cells"][0]["name"], "a");
  EXPECT_EQ(o["cells"][0]["page"], "/cell/a/");
  EXPECT_EQ(o["cells"][0]["mode"], "run");
  EXPECT_EQ(o["cells"][1]["mode"], "run");
  EXPECT_EQ(o["title"], "line test");
  EXPECT_TRUE(o["properties"].is_null());  // this server watches none, and says so
  EXPECT_EQ(o["properties_note"], "no properties watched");
  const auto r = http_post(port, "/cell/b/api/mode", R"({"mode": "stop"})", server->token());
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(b.mode(), RunMode::Stop);
  EXPECT_EQ(a.mode(), RunMode::Run);
  o = overview();
  EXPECT_EQ(o["cells"][0]["mode"], "run");
  EXPECT_EQ(o["cells"][1]["mode"], "stop");
}

// A board as the watcher above the monitor fills it (scenario/property_watcher.h).
class FixedBoard : public monitor::PropertyBoard {
 public:
  monitor::PropertyReport r;
  monitor::PropertyReport report() const override { return r; }
};

monitor::PropertyStatus watched(const std::string& text, uint64_t violations, uint64_t begin_us, uint64_t duration_us,
                                bool ongoing) {
  monitor::PropertyStatus p;
  p.text = text;
  p.where = "w.scenario.yaml:3";
  p.violations = violations;
  p.last_begin_us = begin_us;
  p.last_duration_us = duration_us;
  p.last_ongoing = p.violated = ongoing;
  p.since_us = ongoing ? begin_us : 0;
  if (violations) p.last_values = {{"a.Y0", "ON"}, {"b.D0", "-3"}};
  return p;
}

TEST_F(CellSetTest, OverviewShowsEachWatchedPropertyAndTheLastViolated) {
  auto board = std::make_shared<FixedBoard>();
  board->r.source = "w.scenario.yaml";
  board->r.how = "evaluated after every scan";
  board->r.properties = {watched("never: a.Y0", 0, 0, 0, false), watched("never: b.Y0", 0, 0, 0, false)};
  serve(board);
  // Before the first instant: listed, claiming neither a hold nor a violation.
  auto o = overview();
  ASSERT_EQ(o["properties"].size(), 2u) << o.dump();
  EXPECT_EQ(o["properties"][0]["state"], "not evaluated yet");
  EXPECT_TRUE(o["properties_t_us"].is_null());
  EXPECT_TRUE(o["last_violated"].is_null());
  EXPECT_EQ(o["properties_note"], "2 properties of w.scenario.yaml, evaluated after every scan");
  board->r.evaluated = true;
  board->r.t_us = 12000;
  board->r.properties = {watched("never: a.Y0 and b.D0 < 0", 3, 9000, 3000, true),  // violated since 9 ms
                         watched("always: b.Y0", 1, 10000, 2000, false),             // began later, ended
                         watched("never: b.X0", 0, 0, 0, false)};
  o = overview();
  ASSERT_EQ(o["properties"].size(), 3u) << o.dump();
  EXPECT_EQ(o["properties_t_us"], 12000);
  const auto& p = o["properties"][0];
  EXPECT_EQ(p["text"], "never: a.Y0 and b.D0 < 0");
  EXPECT_EQ(p["where"], "w.scenario.yaml:3");
  EXPECT_EQ(p["state"], "violated");
  EXPECT_EQ(p["since_us"], 9000);
  EXPECT_EQ(p["violations"], 3);
  EXPECT_EQ(p["last"]["begin_us"], 9000);
  EXPECT_EQ(p["last"]["duration_us"], 3000);
  EXPECT_EQ(p["last"]["ongoing"], true);
  EXPECT_EQ(p["last"]["values"][1]["name"], "b.D0");
  EXPECT_EQ(p["last"]["values"][1]["value"], "-3");
  EXPECT_EQ(o["properties"][1]["state"], "holding");
  EXPECT_TRUE(o["properties"][1]["since_us"].is_null());
  EXPECT_EQ(o["properties"][2]["violations"], 0);
  EXPECT_TRUE(o["properties"][2]["last"].is_null());
  // The last violated: the one whose last violation began last, ended or not.
  EXPECT_EQ(o["last_violated"]["text"], "always: b.Y0");
  EXPECT_EQ(o["last_violated"]["begin_us"], 10000);
  EXPECT_EQ(o["last_violated"]["duration_us"], 2000);
  EXPECT_EQ(o["last_violated"]["ongoing"], false);
}

TEST_F(CellSetTest, AWiresEndsAreReadFromTheirOwnCells) {
  serve();
  a.set_input(0, true);  // a's latch: a.Y0 on; b's X0 stays off (nothing carries the wire here)
  scan_both();
  const auto w = overview()["wires"];
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0]["from"], "a.Y0");
  EXPECT_EQ(w[0]["from_value"], 1);
  EXPECT_EQ(w[0]["to_value"], 0);
  EXPECT_EQ(w[0]["error"], "");
  // An end in a cell that is not served: no value, and why.
  EXPECT_TRUE(w[1]["to_value"].is_null());
  EXPECT_NE(w[1]["error"].get<std::string>().find("c.X0"), std::string::npos) << w[1].dump();
}

TEST_F(CellSetTest, AnUnknownCellIs404WithTheReasonAndChangesNothing) {
  serve();
  scan_both();
  const std::string before = state();
  for (const char* target : {"/cell/c/api/status", "/cell/c/", "/cell/A/api/read?a=X0", "/cell//api/status"}) {
    const auto r = http_get(port, target);
    EXPECT_EQ(r.status, 404) << target;
    EXPECT_NE(r.json().value("error", "").find("(cells: a, b)"), std::string::npos) << target << ": " << r.body;
  }
  for (const auto& [target, body] : std::vector<std::pair<std::string, std::string>>{
           {"/cell/c/api/mode", R"({"mode": "stop"})"},
           {"/cell/c/api/write", R"({"address": "D0", "values": [5]})"},
           {"/cell/c/api/force", R"({"address": "X1", "action": "on"})"},
           {"/api/mode", R"({"mode": "stop"})"}}) {
    const auto r = http_post(port, target, body, server->token());
    EXPECT_EQ(r.status, 404) << target;
    EXPECT_FALSE(r.json().value("error", "").empty()) << target;
  }
  // The cells' API is under their names: a bare /api/read says where.
  const auto bare = http_get(port, "/api/read?a=X0");
  EXPECT_EQ(bare.status, 404);
  EXPECT_NE(bare.json().value("error", "").find("/cell/NAME/api/read"), std::string::npos) << bare.body;
  EXPECT_EQ(ws_upgrade(port, "", "", "/cell/c/api/live"), 404);
  EXPECT_EQ(ws_upgrade(port, "", "", "/api/live"), 404);
  EXPECT_EQ(state(), before);
}

TEST_F(CellSetTest, ACellsApiIsTheLoneCellsApiUnderItsName) {
  serve();
  a.set_input(0, true);
  scan_both();
  auto r = http_get(port, "/cell/a/api/read?a=Y0,R0");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["values"]["Y0"], 1);
  EXPECT_EQ(r.json()["values"]["R0"], 7);
  r = http_get(port, "/cell/b/api/read?a=Y0");
  EXPECT_EQ(r.json()["values"]["Y0"], 0);
  ASSERT_EQ(http_post(port, "/cell/b/api/write", R"({"address": "D0", "values": [42]})", server->token()).status, 200);
  EXPECT_EQ(b.read(parse_address("D0"), 1)[0], 42u);
  EXPECT_EQ(a.read(parse_address("D0"), 1)[0], 0u);
  EXPECT_EQ(http_get(port, "/api/session").json()["cells"], nlohmann::json::array({"a", "b"}));
  EXPECT_EQ(http_get(port, "/cell/a/api/session").json()["source"], "cell a");
}

TEST_F(CellSetTest, AQualifiedNameOfAnotherCellIsReadFromIt) {
  serve();
  b.set_input(0, true);
  scan_both();
  auto r = http_get(port, "/cell/a/api/read?a=Y0,b.Y0,a.Y0");
  ASSERT_EQ(r.status, 200) << r.body;
  EXPECT_EQ(r.json()["values"]["Y0"], 0);
  EXPECT_EQ(r.json()["values"]["b.Y0"], 1);
  EXPECT_EQ(r.json()["values"]["a.Y0"], 0);  // the page's own cell by its qualified name
  r = http_get(port, "/cell/a/api/read?a=b.nothing");
  EXPECT_EQ(r.status, 400);
  EXPECT_NE(r.json().value("error", "").find("in cell b"), std::string::npos) << r.body;
  // A page changes its own cell only; another's names are refused before any click.
  r = http_get(port, "/cell/a/api/access?a=b.D0,D0");
  EXPECT_NE(r.json()["b.D0"]["write"].get<std::string>().find("cell b's"), std::string::npos) << r.body;
  EXPECT_EQ(r.json()["D0"]["write"], "");
  // And a page's frames carry it, read from that cell.
  WsClient page(port, "", "", "/cell/a/api/live");
  page.send(R"({"subscribe": {"watch": ["b.Y0", "Y0"], "rate_hz": 50}})");
  const auto f = page.next("frame");
  ASSERT_FALSE(f.is_null());
  EXPECT_EQ(f["values"]["b.Y0"], 1) << f.dump();
  EXPECT_EQ(f["values"]["Y0"], 0) << f.dump();
}

// Hostile targets from a fixed seed: never a crash or a 5xx, every refusal names why, and
// neither cell changes.
TEST_F(CellSetTest, HostileCellTargetsAreRefusedAndChangeNothing) {
  serve();
  scan_both();
  const std::string before = state();
  std::mt19937 rng(20261129);
  const std::vector<std::string> parts = {"/cell/", "a", "b", "c", "/", "..", ".", "%2e", "api", "mode", "write",
                                          "?", "a=", "X0", "//", "%", "\\", "cell", "b.Y0", std::string(300, 'x')};
  const std::vector<std::string> names = {"c", "A", "a.b", "..", "%61", "a%2f", "", " a", "b ", "ab", "a/..",
                                          std::string(5000, 'b')};
  const std::vector<std::string> ends = {"/api/mode", "/api/write", "/api/force", "/api/status", "/api/read?a=X0",
                                         "/api/replay", "/", ""};
  for (int i = 0; i < 400; ++i) {
    // Half of them a real endpoint under a cell that is not there, half any junk.
    std::string target = "/cell/";
    if (i % 2) {
      target += names[rng() % names.size()] + ends[rng() % ends.size()];
    } else {
      const int n = int(rng() % 6);
      for (int k = 0; k < n; ++k) target += parts[rng() % parts.size()];
    }
    HttpCall c;
    c.method = rng() % 2 ? "GET" : "POST";
    c.target = target;
    c.token = server->token();
    c.body = R"({"mode": "stop", "address": "D0", "values": [9], "action": "on"})";
    // Writes the cells allow are not what is tested: only routes that name no real change.
    if (c.method == "POST" && (target.find("/cell/a/") == 0 || target.find("/cell/b/") == 0)) c.method = "GET";
    const auto r = http_call(port, c);
    ASSERT_NE(r.status, 0) << target;
    ASSERT_LT(r.status, 500) << target;
    if (r.status >= 400) {
      EXPECT_FALSE(r.json().value("error", "").empty()) << target << ": " << r.body;
    }
  }
  EXPECT_EQ(state(), before);
}

// A line of one cell (or one nodelet left in a process) still opens on its overview; only
// a lone cell's server (HttpServer of one Source) serves its page at /.
TEST(SourceSet, ASetOfOneOpensOnItsOverviewALoneCellOnItsPage) {
  Plc p;
  p.load_program_text(kProgram, "belt.il");
  monitor::HttpSettings s;
  s.endpoint = "127.0.0.1:0";
  monitor::SourceSet set;
  set.add("only", std::make_unique<monitor::LiveSource>(ServerContext(p), "cell only"));
  monitor::HttpServer line(std::move(set), s);
  line.start();
  EXPECT_EQ(http_get(line.port(), "/api/session").json()["cells"], nlohmann::json::array({"only"}));
  EXPECT_EQ(http_get(line.port(), "/api/read?a=X0").status, 404);
  EXPECT_EQ(http_get(line.port(), "/cell/only/api/read?a=X0").status, 200);
  line.stop();
  monitor::LiveSource source(ServerContext(p), "cell lone");
  monitor::HttpServer lone(source, s);
  lone.start();
  EXPECT_EQ(http_get(lone.port(), "/api/session").json()["source"], "cell lone");
  EXPECT_EQ(http_get(lone.port(), "/api/read?a=X0").status, 200);
  EXPECT_EQ(http_get(lone.port(), "/api/overview").json()["cells"].size(), 1u);
  lone.stop();
}

TEST(SourceSet, RefusesNamesAPathOrAQualifiedNameCouldNotCarry) {
  Plc p;
  monitor::SourceSet set;
  set.add("robot", std::make_unique<monitor::LiveSource>(ServerContext(p), "cell robot"));
  for (const char* bad : {"", "a.b", "a/b", "a b", "robot"})
    EXPECT_THROW(set.add(bad, std::make_unique<monitor::LiveSource>(ServerContext(p), "x")), Error) << bad;
  EXPECT_EQ(set.size(), 1u);
  EXPECT_EQ(set.names(), "robot");
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
