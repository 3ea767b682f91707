// A source that cannot be read for a while (a real PLC whose link is down), as the pages
// see it: the last values read, marked stale with their age and the error, no power flow,
// and the change of state logged once each way (docs/monitor-api.md).
#include <atomic>

#include "monitor_fixture.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace monitor_test {
namespace {

// The test's cell, behind a link the test cuts.
class CutLink : public monitor::LiveSource {
 public:
  using LiveSource::LiveSource;
  monitor::SourceKind kind() const override { return monitor::SourceKind::Remote; }
  monitor::Frame read(const std::vector<Address>& addrs) override {
    if (down) throw CommError("PLC 127.0.0.1:1: link down: read: connection refused");
    return LiveSource::read(addrs);
  }
  std::atomic<bool> down{false};
};

TEST_F(MonitorTest, ALostLinkGivesStaleValuesNoFlowAndOneLogLineEachWay) {
  settings.endpoint = "127.0.0.1:0";
  settings.asset_root = assets_;
  CutLink link(ServerContext(plc), "PLC 127.0.0.1:1");
  monitor::HttpServer http(link, settings);
  http.start();
  WsClient page(http.port());
  page.send(R"({"subscribe":{"networks":[0,1],"watch":["Y0","R0"],"rate_hz":50}})");
  plc.set_input(0, true);
  scan();
  nlohmann::json f;
  for (int i = 0; i < 100 && (f.is_null() || f["scan"] != 1); ++i) f = page.next("frame");
  ASSERT_EQ(f["scan"], 1);
  ASSERT_TRUE(f["stale"].is_null());
  ASSERT_GT(energised(f), 0u);

  link.down = true;
  int stale = 0, down_lines = 0, errors = 0;
  int64_t last_age = -1;
  for (int i = 0; i < 400 && stale < 15; ++i) {
    const auto m = page.next_any();
    ASSERT_FALSE(m.is_null()) << "no message after " << stale << " stale frames";
    if (m["type"] == "error") ++errors;
    if (m["type"] == "log" && m["text"].get<std::string>().find("link down") != std::string::npos) ++down_lines;
    if (m["type"] != "frame" || m["stale"].is_null()) continue;
    ++stale;
    // The last values read, with how old they are and why: never drawn as power flow.
    EXPECT_EQ(m["values"]["Y0"], 1) << m.dump();
    EXPECT_EQ(m["values"]["R0"], 7) << m.dump();
    EXPECT_EQ(m["mode"], "unknown");
    EXPECT_EQ(m["scan"], 1);
    EXPECT_EQ(energised(m), 0u);
    EXPECT_TRUE(m["no_flow"].is_string());
    EXPECT_NE(m["stale"]["error"].get<std::string>().find("link down"), std::string::npos);
    const int64_t age = m["stale"]["age_ms"].get<int64_t>();
    EXPECT_GE(age, last_age);
    last_age = age;
  }
  EXPECT_EQ(stale, 15);
  EXPECT_EQ(down_lines, 1);  // a change of state is logged once, not with every frame
  EXPECT_EQ(errors, 0);

  link.down = false;
  int up_lines = 0;
  bool fresh = false;
  for (int i = 0; i < 400 && !fresh; ++i) {
    const auto m = page.next_any();
    ASSERT_FALSE(m.is_null());
    if (m["type"] == "log" && m["text"].get<std::string>().find("values read again") != std::string::npos) ++up_lines;
    fresh = m["type"] == "frame" && m["stale"].is_null();
    if (fresh) {
      EXPECT_GT(energised(m), 0u);
    }
  }
  EXPECT_TRUE(fresh);
  for (int i = 0; i < 5; ++i) {  // a few more frames: the up line came once
    const auto m = page.next_any();
    if (m["type"] == "log") up_lines += m["text"].get<std::string>().find("values read again") != std::string::npos;
  }
  EXPECT_EQ(up_lines, 1);
  http.stop();
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
