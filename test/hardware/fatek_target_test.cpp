// `plc_cell test --target` on a FATEK PLC: `plc_cell run` serving the demo cell with its
// simulation off stands in for it, over TCP and over a serial pty. The hardware scenario
// passes and leaves no force behind; a PLC found with forces and values has them back; the
// safety rules refuse before anything is written; --dry-run connects to nothing; the demo's
// own scenario shows its refusals and widened windows at file:line; --record and --junit.
#include <netinet/in.h>
#include <sys/socket.h>

#include <fstream>
#include <sstream>

#include "../harness/pty_pair.h"
#include "hardware_fixture.h"
#include "plc_cell/recording/reader.h"

namespace hardware_test {
namespace {

using plc_cell::parse_address;

const std::vector<std::string> kTouched = {"X0", "X1", "X3", "X4", "Y1", "RC0", "R0"};

class FatekTarget : public HardwareTest {
 protected:
  FatekTarget() : plc({"--config", kConveyor, "--no-simulation", "--fatek-tcp", "127.0.0.1:0"}) {}
  int port() const { return port_of(plc, "FATEK TCP"); }
  std::string target() const { return "fatek://" + loopback(port()); }
  RunChild plc;
};

size_t count(const std::string& s, const std::string& what) {
  size_t n = 0;
  for (size_t at = s.find(what); at != std::string::npos; at = s.find(what, at + 1)) ++n;
  return n;
}

TEST_F(FatekTarget, TheHardwareScenarioPassesAndLeavesNoForceBehind) {
  const PlcState before = state_of(port(), kTouched);
  const auto r = test_tool({kConveyorScenario, "--target", target()});
  EXPECT_EQ(r.status, 0) << r.out;
  // The first line names the PLC and what will be forced.
  EXPECT_EQ(r.out.rfind("plc_cell test on FATEK tcp " + loopback(port()) + " station 1 (--target " + target() +
                            "): forces stop_button (X1), start_button (X0), part_present (X3), stopper_down (X4), "
                            "stopper_lower (Y1); writes RC0\n",
                        0),
            0u)
      << r.out;
  EXPECT_NE(r.out.find("connected: the PLC is in RUN; resolution "), std::string::npos) << r.out;
  EXPECT_EQ(count(r.out, "PASS  "), 4u) << r.out;
  EXPECT_NE(r.out.find("== 4 passed, 0 failed on FATEK"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; the PLC is as it was found\n"), std::string::npos) << r.out;
  const PlcState after = state_of(port(), kTouched);
  EXPECT_EQ(std::count(after.forced.begin(), after.forced.end(), true), 0) << describe(after, kTouched);
  EXPECT_TRUE(after == before) << describe(before, kTouched) << "\n" << describe(after, kTouched);
}

TEST_F(FatekTarget, ForcesAndValuesFoundBeforeTheRunAreThereAfterIt) {
  plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport(loopback(port())));
  // Someone left the part sensor forced ON and the stopper forced OFF, and the count at 7.
  c.control(parse_address("X3"), plc_cell::fatek::Action::Disable);
  c.control(parse_address("X3"), plc_cell::fatek::Action::Set);
  c.control(parse_address("Y1"), plc_cell::fatek::Action::Disable);
  c.control(parse_address("Y1"), plc_cell::fatek::Action::Reset);
  c.write(parse_address("RC0"), {7});
  // The program mirrors the count in R0 at its next scan.
  for (int i = 0; i < 1000 && c.read(parse_address("R0"), 1).at(0) != 7; ++i) {
  }
  ASSERT_EQ(c.read(parse_address("R0"), 1).at(0), 7u) << "R0 never mirrored RC0 in 1000 reads";
  const PlcState before = state_of(port(), kTouched);
  const auto r = test_tool({kConveyorScenario, "--target", target(), "-k", "forced up"});
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("part_present (X3): forced ON as found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("stopper_lower (Y1): forced OFF as found"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("RC0: written back, 7 as found"), std::string::npos) << r.out;
  const PlcState after = state_of(port(), kTouched);
  EXPECT_TRUE(after == before) << describe(before, kTouched) << "\n" << describe(after, kTouched);
}

TEST_F(FatekTarget, APlcInStopIsRefusedAndNothingIsWritten) {
  plc_cell::fatek::Client(plc_cell::fatek::tcp_transport(loopback(port()))).set_run(false);
  const PlcState before = state_of(port(), kTouched);
  const auto r = test_tool({kConveyorScenario, "--target", target()});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find(kConveyorScenario + ":9: error: key 'hardware': the PLC is in STOP; this file requires RUN"),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("no case ran, nothing was written"), std::string::npos) << r.out;
  EXPECT_TRUE(state_of(port(), kTouched) == before);
}

TEST_F(FatekTarget, AFileRunsOnlyOnTheTargetsItAllows) {
  std::ifstream in(kConveyorScenario);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s.replace(s.find("cell: conveyor.yaml"), 19, "cell: " + kConveyor);
  const std::string only = temp() + "/only.scenario.yaml";
  std::string listed = s;
  listed.replace(listed.find("hardware: true"), 14, "hardware: [fatek://10.0.0.5:*]");
  std::ofstream(only) << listed;
  const PlcState before = state_of(port(), kTouched);
  auto r = test_tool({only, "--target", target()});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find(only + ":9: error: key 'hardware': this file allows only the targets fatek://10.0.0.5:*, not " +
                       target()),
            std::string::npos)
      << r.out;
  const std::string none = temp() + "/none.scenario.yaml";
  std::string unmarked = s;
  unmarked.erase(unmarked.find("hardware: true"), unmarked.find('\n', unmarked.find("hardware: true")) -
                                                      unmarked.find("hardware: true"));
  std::ofstream(none) << unmarked;
  r = test_tool({none, "--target", target()});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find(none + ":1: error: key 'hardware': this file does not say that it may run on a PLC"),
            std::string::npos)
      << r.out;
  EXPECT_TRUE(state_of(port(), kTouched) == before);
}

// The demo's own scenario counts on a fresh cell and its simulation: against the PLC it
// shows, each at its line, that it does not allow hardware and the windows a link cannot
// honour, and with --tolerance the same windows widened.
TEST_F(FatekTarget, TheDemosOwnScenarioShowsItsRefusalsAndWidenedWindowsAtTheirLines) {
  const PlcState before = state_of(port(), kTouched);
  auto r = test_tool({kDemoScenario, "--target", target()});
  EXPECT_EQ(r.status, 1) << r.out;
  const std::string f = kDemoScenario + ":";
  for (const std::string& line : std::vector<std::string>{
           f + "1: error: key 'hardware': this file does not say that it may run on a PLC",
        f + "35: error: key 'expect_sequence': entry 2's within 0 ms is tighter than the resolution ",
        f + "36: error: key 'expect_sequence': entry 3's between [1.500 s, 1.501 s] is tighter than the resolution ",
        f + "37: error: key 'expect_sequence': entry 4's within 1 ms is tighter than the resolution "})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  r = test_tool({kDemoScenario, "--target", target(), "--tolerance", "1s"});
  EXPECT_EQ(r.status, 1) << r.out;
  // Its properties are checked with the resolution as their grace, and say so.
  EXPECT_NE(r.out.find(f + "10: property never: pick_request and stopper_lower: its grace within 1 ms, checked with "
                           "the resolution "),
            std::string::npos)
      << r.out;
  for (const std::string& line : std::vector<std::string>{f + "35: entry 2's within 0 ms widened by ",
                                  f + "36: entry 3's between [1.500 s, 1.501 s] widened by ",
                                  f + "37: entry 4's within 1 ms widened by "})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
  EXPECT_EQ(r.out.find("tighter than the resolution"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(f + "1: error: key 'hardware'"), std::string::npos) << r.out;
  EXPECT_TRUE(state_of(port(), kTouched) == before);
}

TEST_F(FatekTarget, ADryRunListsEveryWriteAndForceAndConnectsToNothing) {
  // A listener nobody should reach: it counts the connections made to it.
  const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  ASSERT_EQ(::listen(s, 4), 0);
  socklen_t len = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  const auto r = test_tool({kConveyorScenario, "--target", "fatek://" + loopback(ntohs(a.sin_port)), "--dry-run",
                            "-k", "forced up"});
  EXPECT_EQ(::accept(s, nullptr, nullptr), -1);  // no connection was made
  ::close(s);
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string f = kConveyorScenario + ":";
  for (const std::string& line : std::vector<std::string>{
           "case " + kConveyorScenario + ": a part held at the sensor keeps the belt stopped while the stopper is forced up",
        "  " + f + "15: force stop_button (X1) OFF (held as its terminal)", "  " + f + "16: write stopper_lower (Y1) = off",
        "  " + f + "16: write RC0 = 0", "  " + f + "18: force stop_button (X1) ON (held as its terminal)",
        "  " + f + "74: force start_button (X0) ON, then OFF after 200 ms", "  " + f + "77: force stopper_lower (Y1) OFF",
        "  " + f + "78: force part_present (X3) ON (held as its terminal)",
        "  " + f + "83: release every point this case forced",
        "  then put back as found: stop_button (X1), start_button (X0), part_present (X3), stopper_down (X4), "
        "stopper_lower (Y1), RC0",
        "dry run: nothing was sent to the PLC; time windows are checked against the resolution once connected"})
    EXPECT_NE(r.out.find(line + "\n"), std::string::npos) << line << "\n" << r.out;
}

TEST_F(FatekTarget, AFailingCaseIsRecordedAsPolledAndTheJUnitNamesTheTarget) {
  std::ifstream in(kConveyorScenario);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  s.replace(s.find("cell: conveyor.yaml"), 19, "cell: " + kConveyor);
  s.replace(s.find("expect: R0 == 1 and RC0 == 1"), 28, "expect: R0 == 2 and RC0 == 1");  // wrong on purpose
  const std::string file = temp() + "/wrong.scenario.yaml";
  std::ofstream(file) << s;
  const std::string junit = temp() + "/results.xml", dir = temp() + "/rec";
  const auto r = test_tool({file, "--target", target(), "-k", "counted", "--record", dir, "--junit", junit});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("FAIL  " + file + ": a part is picked, released and counted"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("recorded: plc_cell monitor --recording " + dir + "/"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; the PLC is as it was found"), std::string::npos) << r.out;
  const auto rec = plc_cell::recording::Reader::load(dir + "/a_part_is_picked__released_and_counted.plcrec");
  EXPECT_NE(rec.info().source.find("values polled over FATEK tcp " + loopback(port()) + " station 1: "),
            std::string::npos)
      << rec.info().source;
  EXPECT_NE(rec.info().source.find("the rest of memory was not read"), std::string::npos);
  ASSERT_TRUE(rec.info().failure_us);
  EXPECT_NE(rec.info().failure.find("expect R0 == 2"), std::string::npos) << rec.info().failure;
  EXPECT_GT(rec.scans(), 100u);
  std::ifstream j(junit);
  std::stringstream x;
  x << j.rdbuf();
  EXPECT_NE(x.str().find("<testsuite name=\"wrong.scenario on " + target() + "\""), std::string::npos) << x.str();
  EXPECT_NE(x.str().find("<property name=\"resolution\" value=\""), std::string::npos) << x.str();
  EXPECT_NE(x.str().find("<property name=\"windows widened\" value=\"" + file +
                         ":22: property never: conveyor_run and not line_running: no grace, checked with the "
                         "resolution "),
            std::string::npos)
      << x.str();
  EXPECT_NE(x.str().find("<property name=\"left as found\" value=\"yes\"/>"), std::string::npos) << x.str();
}

TEST_F(HardwareTest, OverASerialLineThroughSocat) {
  plc_cell::testing::PtyPair line(temp());
  RunChild plc({"--config", kConveyor, "--no-simulation", "--fatek-serial", line.b, "--fatek-tcp", "127.0.0.1:0"});
  wait_scanning(plc);
  const int port = port_of(plc, "FATEK TCP");
  const PlcState before = state_of(port, kTouched);
  const auto r = test_tool({kConveyorScenario, "--target", "fatek-serial:" + line.a, "-k", "stop button"});
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("PASS  " + kConveyorScenario + ": the stop button stops the line"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; the PLC is as it was found"), std::string::npos) << r.out;
  EXPECT_TRUE(state_of(port, kTouched) == before);
}

// The stand-in as a real cell: with --no-simulation nothing plays the inputs (the demo's
// normally closed stop button stays OFF, a written part sensor stays ON); without it the
// simulation plays them.
TEST_F(HardwareTest, PlcCellRunWithNoSimulationLeavesTheInputsAsTheClientsLeaveThem) {
  RunChild off({"--config", kConveyor, "--no-simulation", "--fatek-tcp", "127.0.0.1:0"});
  wait_scanning(off);
  EXPECT_NE(off.log.find("plc_cell run: simulation off: X1, X3, X4 stay as the clients leave them"), std::string::npos)
      << off.log;
  plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport(loopback(port_of(off, "FATEK TCP"))));
  c.write(parse_address("X3"), {1});
  for (int i = 0; i < 200; ++i) {  // 200 reads: many scans of 1 ms
    const auto v = c.read_mixed({parse_address("X1"), parse_address("X3"), parse_address("M0")});
    ASSERT_EQ(v, (std::vector<uint32_t>{0, 1, 0})) << "read " << i;
  }
  RunChild on({"--config", kConveyor, "--fatek-tcp", "127.0.0.1:0"});
  wait_scanning(on);
  plc_cell::fatek::Client d(plc_cell::fatek::tcp_transport(loopback(port_of(on, "FATEK TCP"))));
  bool played = false;
  for (int i = 0; i < 1000 && !played; ++i) played = d.read(parse_address("X1"), 1).at(0) == 1;
  EXPECT_TRUE(played) << "the simulation never played the stop button (X1) in 1000 reads";
}

}  // namespace
}  // namespace hardware_test
