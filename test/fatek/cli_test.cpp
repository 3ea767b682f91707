// `plc_cell fatek` against `plc_cell run --fatek-tcp`: output and exit status.
#include <gtest/gtest.h>

#include "../core/run_tool.h"

#include <chrono>
#include <stdexcept>
#include <string>

namespace {

using Result = plc_cell::testing::ToolResult;
Result sh(const std::string& cmd) { return plc_cell::testing::run_shell(cmd); }

// `plc_cell run` serving FATEK on a free port; the port is read back from its log line.
class RunServer {
 public:
  RunServer()
      : proc_({PLC_CELL_TOOL, "run", "--program", std::string(PLC_CELL_SOURCE_DIR) + "/test/fatek/bridge_cell.il",
               "--fatek-tcp", "127.0.0.1:0", "--station", "2"}) {
    // "serving FATEK TCP 127.0.0.1:PORT station 2"
    const bool up = proc_.read_until(
        [](const std::string& log) {
          const auto k = log.find("FATEK TCP 127.0.0.1:");
          return k != std::string::npos && log.find(" station", k) != std::string::npos;
        },
        std::chrono::seconds(20));
    if (!up) throw std::runtime_error("plc_cell run did not start: " + proc_.output());
    port = std::stoi(proc_.output().substr(proc_.output().find("FATEK TCP 127.0.0.1:") + 20));
  }
  ~RunServer() { proc_.end(); }
  std::string fatek(const std::string& args) const {
    return std::string(PLC_CELL_TOOL) + " fatek --tcp 127.0.0.1:" + std::to_string(port) + " --station 2 " + args;
  }
  int port = 0;

 private:
  plc_cell::testing::ChildProcess proc_;
};

}  // namespace

TEST(FatekCli, TalksToPlcCellRun) {
  RunServer s;
  Result r = sh(s.fatek("status"));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("RUN"), std::string::npos) << r.out;
  r = sh(s.fatek("write R11 5 0x7"));
  EXPECT_EQ(r.status, 0) << r.out;
  r = sh(s.fatek("read R11 2"));
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("R11      5 (0x0005"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("R12      7 (0x0007"), std::string::npos) << r.out;
  r = sh(s.fatek("force Y9 disable"));
  EXPECT_EQ(r.status, 0) << r.out;
  r = sh(s.fatek("disabled Y8 2"));
  EXPECT_NE(r.out.find("Y9       disabled"), std::string::npos) << r.out;
  r = sh(s.fatek("loopback HELLO"));
  EXPECT_EQ(r.out, "HELLO\n");
  r = sh(s.fatek("stop"));
  EXPECT_EQ(r.status, 0) << r.out;
  r = sh(s.fatek("status"));
  EXPECT_NE(r.out.find("STOP"), std::string::npos) << r.out;
  r = sh(s.fatek("run"));
  EXPECT_EQ(r.status, 0) << r.out;
}

TEST(FatekCli, ErrorsGiveNonZeroStatus) {
  RunServer s;
  Result r = sh(s.fatek("read R8000 100"));  // past R8071: refused before sending
  EXPECT_EQ(r.status, 1) << r.out;
  r = sh(s.fatek("frobnicate"));
  EXPECT_EQ(r.status, 2) << r.out;
  r = sh(std::string(PLC_CELL_TOOL) + " fatek --tcp 127.0.0.1:" + std::to_string(s.port) +
         " --station 9 --timeout 100 --retries 0 status");  // nobody answers station 9
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("no answer"), std::string::npos) << r.out;
}
