// `plc_cell monitor` as users start it: on a failed case's recording, opened at the failure
// and moved through the page's API; on `plc_cell run` standing in for a real FATEK PLC; and
// the usages it refuses. The port is read from the command's own log line (port 0).
#include <gtest/gtest.h>

#include "../monitor/client.h"
#include "../reliability/run_child.h"
#include "helpers.h"
#include "plc_cell/recording/reader.h"

namespace plc_cell {
namespace {

using monitor_test::http_get;
using monitor_test::http_post;

const std::string kExamples = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/";

TEST(MonitorCommand, ARecordingOpensAtItsFailureAndIsReadOnly) {
  const std::string dir = testing::scratch_dir("monitor");
  testing::run_tool("test " + kExamples + "too_strict.fails.yaml --record " + dir);
  const std::string file = dir + "/the_stopper_lowers_1_s_after_the_part_arrives.plcrec";
  RunChild monitor({"--recording", file, "--open-at", "failure", "--http-tcp", "127.0.0.1:0", "--http-writable", "all"},
                   1, 20000, "monitor");
  ASSERT_EQ(monitor.ports.size(), 1u) << monitor.log;
  const uint16_t port = uint16_t(monitor.ports[0]);
  nlohmann::json replay = http_get(port, "/api/replay").json();
  EXPECT_EQ(replay["cursor_us"], 2000000u) << replay.dump();
  EXPECT_EQ(replay["failure_us"], 2000000u);
  EXPECT_EQ(replay["scans"], 2001u);
  // The failing check's text, as the report printed it and the file keeps it.
  const std::string failure = recording::Reader::load(file).info().failure;
  EXPECT_NE(failure.find("stopper_lower"), std::string::npos) << failure;
  EXPECT_EQ(replay["failure"], failure) << replay.dump();
  // The recorded history of a trend: the robot called once, at 1 s.
  const nlohmann::json history = http_get(port, "/api/replay/history?a=pick_request&from_us=0&to_us=2000000").json();
  EXPECT_EQ(history["series"]["pick_request"], nlohmann::json::parse("[[0, 0], [1000000, 1]]")) << history.dump();
  EXPECT_TRUE(history["cut_us"].is_null());
  EXPECT_EQ(http_get(port, "/api/replay/history?a=no_such_name").status, 400);
  const nlohmann::json values = http_get(port, "/api/read?a=stopper_lower,pick_request").json()["values"];
  EXPECT_EQ(values["stopper_lower"], 0);
  EXPECT_EQ(values["pick_request"], 1);
  const std::string token = http_get(port, "/api/session").json().value("token", "");
  EXPECT_EQ(http_get(port, "/api/session").json().value("kind", ""), "replay");
  replay = http_post(port, "/api/replay", R"({"step": "scan", "n": -1000})", token).json();
  EXPECT_EQ(replay["cursor_us"], 1000000u) << replay.dump();
  EXPECT_EQ(http_get(port, "/api/read?a=pick_request").json()["values"]["pick_request"], 1);
  replay = http_post(port, "/api/replay", R"({"step": "scan", "n": -1})", token).json();
  EXPECT_EQ(http_get(port, "/api/read?a=pick_request").json()["values"]["pick_request"], 0);  // before the part
  // A step by event refused for a name it cannot watch moves nothing.
  EXPECT_EQ(http_post(port, "/api/replay", R"({"step": "event", "n": 1, "watch": ["no_such_name"]})", token).status, 400);
  EXPECT_EQ(http_get(port, "/api/replay").json()["cursor_us"], 999000u);
  replay = http_post(port, "/api/replay", R"({"step": "event", "n": 1, "watch": ["D0"]})", token).json();
  EXPECT_EQ(replay["cursor_us"], 1000000u) << replay.dump();  // the part, not the 0.01 s clock relay
  const monitor_test::HttpReply w = http_post(port, "/api/write", R"({"address": "D0", "values": [5]})", token);
  EXPECT_GE(w.status, 400);
  EXPECT_NE(w.body.find("a recording is read-only"), std::string::npos) << w.body;
}

TEST(MonitorCommand, PlcCellRunAsARealFatekPlc) {
  RunChild plc({"--config", kExamples + "conveyor.yaml", "--fatek-tcp", "127.0.0.1:0"});
  ASSERT_EQ(plc.ports.size(), 1u) << plc.log;
  RunChild monitor({"--fatek", "127.0.0.1:" + std::to_string(plc.ports[0]), "--config", kExamples + "conveyor.yaml",
                    "--http-tcp", "127.0.0.1:0"},
                   1, 20000, "monitor");
  ASSERT_EQ(monitor.ports.size(), 1u) << monitor.log;
  const uint16_t port = uint16_t(monitor.ports[0]);
  EXPECT_EQ(http_get(port, "/api/session").json().value("kind", ""), "remote");
  nlohmann::json r;
  for (int i = 0; i < 200 && r["values"]["line_running"] != 1; ++i) r = http_get(port, "/api/read?a=line_running").json();
  EXPECT_EQ(r["values"]["line_running"], 1) << r.dump();
  EXPECT_EQ(r["mode"], "run");
  const nlohmann::json status = http_get(port, "/api/status").json();
  EXPECT_EQ(status["note"], "power flow computed from polled values");
  ASSERT_EQ(status["servers"].size(), 1u);
  EXPECT_EQ(status["servers"][0]["link_up"], true);
  plc.kill9();
  const monitor_test::HttpReply down = http_get(port, "/api/read?a=line_running");
  EXPECT_GE(down.status, 400);
  EXPECT_NE(down.body.find("link down"), std::string::npos) << down.body;
  EXPECT_EQ(http_get(port, "/api/status").json()["servers"][0]["link_up"], false);
}

TEST(MonitorCommand, RefusedUsages) {
  auto r = testing::run_tool("monitor --http-tcp 127.0.0.1:0");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("give one of --recording FILE"), std::string::npos) << r.out;
  r = testing::run_tool("monitor --fatek 127.0.0.1:1 --open-at failure --program " + kExamples + "conveyor.il");
  EXPECT_NE(r.out.find("--open-at goes with --recording"), std::string::npos) << r.out;
  r = testing::run_tool("monitor --tri /nonexistent/ttyUSB0 --program " + kExamples + "conveyor.il");
  EXPECT_EQ(r.status, 2) << r.out;
  EXPECT_NE(r.out.find("plc_cell monitor: --tri: endpoint '/nonexistent/ttyUSB0': no such device"), std::string::npos)
      << r.out;
  const std::string dir = testing::scratch_dir("monitor_usage");
  const std::string rec = testing::record_conveyor(dir, "10ms");
  r = testing::run_tool("monitor --recording " + rec + " --open-at failure --http-tcp 127.0.0.1:0");
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.out.find(rec + " has no failure"), std::string::npos) << r.out;
  r = testing::run_tool("monitor --recording " + rec + " --open-at soon --http-tcp 127.0.0.1:0");
  EXPECT_NE(r.out.find("--open-at soon: failure or a time"), std::string::npos) << r.out;
  r = testing::run_tool("monitor --recording " + kExamples + "conveyor.il --http-tcp 127.0.0.1:0");
  EXPECT_NE(r.out.find("conveyor.il: offset 0: not a plc_cell recording"), std::string::npos) << r.out;
}

}  // namespace
}  // namespace plc_cell
