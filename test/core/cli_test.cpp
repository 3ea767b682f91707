// The plc_cell command-line tool, run as a user would run it.
#include <gtest/gtest.h>

#include "run_tool.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using Result = plc_cell::testing::ToolResult;
Result tool(const std::string& args) { return plc_cell::testing::run_tool(args); }

std::string slurp(const std::string& path) {
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

const std::string kDemo = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.yaml";

}  // namespace

TEST(Cli, SimPrintsTheWatchedValuesAndIsDeterministic) {
  const std::string args = "sim --config " + kDemo +
                           " --duration 12s --watch conveyor_run,R0,T50 --trace /tmp/plc_cell_cli_test_";
  const Result a = tool(args + "a.csv");
  const Result b = tool(args + "b.csv");
  ASSERT_EQ(a.status, 0) << a.out;
  EXPECT_EQ(a.out, b.out);
  EXPECT_EQ(slurp("/tmp/plc_cell_cli_test_a.csv"), slurp("/tmp/plc_cell_cli_test_b.csv"));
  EXPECT_EQ(a.out,
            "# plc_cell sim: 12000 scans of 1000 us, virtual time 12.000000 s, RUN\n"
            "conveyor_run = 0\n"
            "R0 = 2\n"
            "T50 = 0\n");
  const std::string trace = slurp("/tmp/plc_cell_cli_test_a.csv");
  EXPECT_EQ(trace.rfind("time_s,address,value,event,source\n0.000000,conveyor_run,1\n0.000000,R0,0\n0.000000,T50,0\n"
                        "1.000000,conveyor_run,0\n2.500000,T50,1\n2.501000,conveyor_run,1\n",
                        0),
            0u)
      << trace;
  EXPECT_NE(trace.find("8.501000,R0,2\n"), std::string::npos);
}

TEST(Cli, SimSetsAddressesBeforeTheRun) {
  const std::string prog = "/tmp/plc_cell_cli_add.il";
  std::ofstream(prog) << "ORG M1925\nADD Sa=R1 Sb=R2 D=R3\nORG X0\nOUT Y0\nEND\n";
  const Result r = tool("sim --program " + prog + " --duration 10ms --scan 2ms --set R1=40 --set R2=0x2 --set X0=1 --watch R3,Y0");
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(r.out, "# plc_cell sim: 5 scans of 2000 us, virtual time 0.010000 s, RUN\nR3 = 42\nY0 = 1\n");
}

TEST(Cli, CheckListsEveryErrorAndFails) {
  const std::string prog = "/tmp/plc_cell_cli_bad.il";
  std::ofstream(prog) << "ORG X0\nOUT Q1\nTMR T1\nEND\n";
  const Result r = tool("check --program " + prog);
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.out.find(prog + ":2:5: error: bad address 'Q1'"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(prog + ":3:1: error: TMR takes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("2 error(s)"), std::string::npos);
  const Result ok = tool("check --program " + std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.il");
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_NE(ok.out.find("OK, 27 instructions"), std::string::npos) << ok.out;
}

TEST(Cli, UsageErrorsExitWithTwo) {
  EXPECT_EQ(tool("").status, 2);
  EXPECT_EQ(tool("frobnicate").status, 2);
  const Result r = tool("sim --config " + kDemo);
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("missing --duration"), std::string::npos);
  EXPECT_EQ(tool("sim --bogus 1").status, 2);
  const Result bad = tool("sim --config " + kDemo + " --duration 1s --watch Q7");
  EXPECT_EQ(bad.status, 1);
  EXPECT_NE(bad.out.find("'Q7' is neither a signal"), std::string::npos) << bad.out;
}

TEST(Cli, RunStopsAfterItsDuration) {
  const Result r = tool("run --config " + kDemo + " --duration 300ms");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("scans, cycle avg"), std::string::npos) << r.out;
}

TEST(Cli, RunRejectsABadPriority) {
  const Result r = tool("run --config " + kDemo + " --duration 10ms --rt-priority high");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.out.find("--rt-priority takes a whole number, got 'high'"), std::string::npos) << r.out;
  EXPECT_EQ(tool("run --config " + kDemo + " --duration 10ms --rt-priority 100").status, 2);
}

// Every server setting is an option, from the server kinds' schemas, checked as the YAML's.
TEST(Cli, ServerOptionsComeFromTheSchemas) {
  const Result help = tool("--help");
  EXPECT_EQ(help.status, 0);
  EXPECT_NE(help.out.find("--modbus-gateway-wait DURATION [150ms]"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--fatek-station N (or --station) [1]"), std::string::npos) << help.out;
  const struct {
    const char* args;
    const char* error;
  } refused[] = {
      {"run --duration 10ms --modbus-id 300", "--modbus-id 300: value out of range [1, 247]"},
      {"run --duration 10ms --modbus-gateway-wait 150", "--modbus-gateway-wait 150: value out of range [0.001, 60] s"},
      {"run --duration 10ms --modbus-tcp :0 --modbus-tcp :1", "--modbus-tcp given more than once"},
      {"sim --duration 10ms --scan 2s", "--scan 2s: value out of range [0.0001, 1] s"},
  };
  for (const auto& c : refused) {
    const Result r = tool(std::string(c.args) + " --config " + kDemo);
    EXPECT_EQ(r.status, 2) << c.args;
    EXPECT_NE(r.out.find(c.error), std::string::npos) << c.args << "\n" << r.out;
  }
  const Result served = tool("run --config " + kDemo + " --duration 50ms --fatek-tcp 127.0.0.1:0 --station 7");
  EXPECT_EQ(served.status, 0) << served.out;
  EXPECT_NE(served.out.find("serving FATEK TCP 127.0.0.1:"), std::string::npos) << served.out;
  EXPECT_NE(served.out.find("station 7"), std::string::npos) << served.out;
}

TEST(Cli, CheckKnowsEveryInstalledFunction) {
  const std::string prog = "/tmp/plc_cell_cli_funs.il";
  std::ofstream(prog) << "ORG M0\nLD M1\nLD M2\nFUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2\n"
                         "ORG M3\nLD M4\nLD M5\nFUN 150 Pt=2 SR=R300 WR=R400 ACT=M10 ERR=M11 DN=M12\nEND\n";
  const Result r = tool("check --program " + prog);
  EXPECT_EQ(r.status, 0) << r.out;
}

// ---- check --config: the cell built as sim builds it, then stopped ----------------------

namespace {

const std::string kCheckDir = "/tmp/plc_cell_check_";

// A cell file beside a valid program (cell.program is relative to the file).
std::string write_cell(const std::string& name, const std::string& yaml) {
  std::ofstream(kCheckDir + "ok.il") << "ORG M0\nOUT Y0\nEND\n";
  const std::string path = kCheckDir + name + ".yaml";
  std::ofstream(path) << "cell: {program: plc_cell_check_ok.il}\n" << yaml;
  return path;
}

// check and sim on the same cell: the same exit status and the same error lines
// (check adds its count).
void expect_check_agrees_with_sim(const std::string& path, const std::string& what) {
  const Result check = tool("check --config " + path);
  const Result sim = tool("sim --config " + path + " --duration 10ms");
  EXPECT_EQ(check.status, sim.status) << what << "\ncheck:\n" << check.out << "sim:\n" << sim.out;
  if (sim.status == 0) {
    EXPECT_NE(check.out.find(": OK"), std::string::npos) << what << "\n" << check.out;
    return;
  }
  size_t lines = 0;
  for (char c : sim.out) lines += c == '\n';
  EXPECT_EQ(check.out, sim.out + std::to_string(lines) + " error(s)\n") << what;
}

// The four cells an outside check found accepted by `check --config` but refused by `sim`.
struct Rejection {
  const char* name;
  const char* yaml;
  const char* error;  // after the file name: line:column: error: message
};
const Rejection kReported[] = {
    {"motion_42",
     "axes:\n  pso0:\n    table:\n      at: R0\n      text: |\n        001 SPD 10000\n"
     "            DRVC ADR,+,20000,Ut\n            GOTO NEXT\n        002 SPD 5000\n"
     "            DRVZ MD2\n            GOTO 1\n        MEND\n",
     // at the step's first line, its SPD (docs/motion.md)
     ":10:1: error: key 'axes.pso0.table.text': error 42: step 2: DRVZ can't follow DRVC"},
    {"x5_twice", "counters:\n  hsc6: {mode: MD0, a: X5}\n  hsc7: {mode: MD0, a: X5}\n",
     ":4:24: error: key 'counters.hsc7.a': X5 is already used as the U input of HSC6 (line 3)"},
    {"hsc9", "counters:\n  hsc9: {mode: MD0}\n", ":3:3: error: key 'counters.hsc9': unknown key"},
    {"module_7tc", "modules:\n  temperature:\n    modules:\n      - {type: 7TC}\n",
     ":5:16: error: key 'modules.temperature.modules[0].type': unknown module '7TC'"},
};

}  // namespace

TEST(CheckConfig, RejectsWhatSimRejects) {
  for (const auto& c : kReported) {
    const std::string path = write_cell(c.name, c.yaml);
    const Result check = tool("check --config " + path);
    EXPECT_EQ(check.status, 1) << c.name << "\n" << check.out;
    EXPECT_NE(check.out.find(path + c.error), std::string::npos) << c.name << "\n" << check.out;
    expect_check_agrees_with_sim(path, c.name);
  }
}

TEST(CheckConfig, ReportsEveryErrorOfTheFileInOneRun) {
  const std::string path = write_cell("many",
                                      "plc: {scan_period: 5, watchdog: 0.2, bogus: 1}\n"    // 2
                                      "signals: {a: Q1, b: X1}\n"                            // 3
                                      "simulation:\n"                                        // 4
                                      "  inputs:\n"                                          // 5
                                      "    X2: {pulse: {period: 1, width: 2}}\n"             // 6
                                      "    X3: {steps: [[1, 1], [0.5, 0]]}\n"                // 7
                                      "counters:\n"                                          // 8
                                      "  hsc9: {mode: MD0}\n"                                // 9
                                      "modules:\n"                                           // 10
                                      "  temperature:\n"                                     // 11
                                      "    modules:\n"                                       // 12
                                      "      - {type: 7TC}\n"                                // 13
                                      "servers:\n"                                           // 14
                                      "  fatek: {tcp: localhost}\n"                          // 15
                                      "frobnicate: 1\n");                                    // 16
  const Result r = tool("check --config " + path);
  EXPECT_EQ(r.status, 1);
  const char* want[] = {
      ":2:20: error: key 'plc.scan_period': value 5 out of range [0.0001, 1]\n",
      ":2:38: error: key 'plc.bogus': unknown key",
      ":3:14: error: key 'signals.a': bad address 'Q1'",
      ":6:36: error: key 'simulation.inputs.X2.pulse.width': longer than the period\n",
      ":7:27: error: key 'simulation.inputs.X3.steps[1]': times must not decrease\n",
      ":9:3: error: key 'counters.hsc9': unknown key",
      ":13:16: error: key 'modules.temperature.modules[0].type': unknown module '7TC'",
      ":15:16: error: key 'servers.fatek.tcp': 'localhost': expected HOST:PORT",
      ":16:1: error: key 'frobnicate': unknown key",
  };
  size_t at = 0;
  for (const char* w : want) {  // each once, in file order
    const size_t pos = r.out.find(path + w);
    EXPECT_NE(pos, std::string::npos) << w << "\n" << r.out;
    if (pos == std::string::npos) continue;
    EXPECT_GT(pos + 1, at) << w << " out of order\n" << r.out;
    at = pos;
  }
  EXPECT_NE(r.out.find("\n9 error(s)\n"), std::string::npos) << r.out;
  expect_check_agrees_with_sim(path, "many");
}

// Within modules.temperature.modules and modules.plants each entry is read on its own.
TEST(CheckConfig, ReportsEveryBadModuleEntry) {
  const std::string path = write_cell("modules2",
                                      "modules:\n"
                                      "  temperature:\n"
                                      "    modules:\n"
                                      "      - {type: 7TC}\n"                              // 5
                                      "      - {type: 6RTD, sensor: K}\n"                  // 6
                                      "      - {type: 2TC, channels: [{value: 1 ohm}]}\n"  // 7
                                      "  plants:\n"
                                      "    - {name: a, gain: -1}\n"                        // 9
                                      "    - {nmae: b}\n");                                // 10
  const Result r = tool("check --config " + path);
  EXPECT_EQ(r.status, 1);
  for (const char* w : {":5:16: error: key 'modules.temperature.modules[0].type': unknown module '7TC'",
                        ":6:30: error: key 'modules.temperature.modules[1].sensor': an RTD module takes PT100 or PT1000",
                        ":7:40: error: key 'modules.temperature.modules[2].channels[0].value': a thermocouple's value is in mV",
                        ":9:23: error: key 'modules.plants[0].gain': value -1 out of range",
                        ":10:8: error: key 'modules.plants[1].nmae': unknown key"})
    EXPECT_NE(r.out.find(path + w), std::string::npos) << w << "\n" << r.out;
  EXPECT_NE(r.out.find("\n5 error(s)\n"), std::string::npos) << r.out;
  expect_check_agrees_with_sim(path, "modules2");
}

TEST(CheckConfig, ProgramErrorsComeAfterTheCellErrors) {
  std::ofstream(kCheckDir + "bad.il") << "ORG X0\nOUT Q1\nEND\n";
  const std::string path = kCheckDir + "badprog.yaml";
  std::ofstream(path) << "cell: {program: plc_cell_check_bad.il}\nplc: {watchdog: 99}\n";
  const Result r = tool("check --config " + path);
  EXPECT_EQ(r.status, 1);
  const size_t cfg = r.out.find(path + ":2:17: error: key 'plc.watchdog'");
  const size_t prog = r.out.find(kCheckDir + "bad.il:2:5: error: bad address 'Q1'");
  EXPECT_NE(cfg, std::string::npos) << r.out;
  EXPECT_NE(prog, std::string::npos) << r.out;
  EXPECT_LT(cfg, prog) << r.out;
  EXPECT_NE(r.out.find("2 error(s)"), std::string::npos) << r.out;
  expect_check_agrees_with_sim(path, "badprog");
}

TEST(CheckConfig, AgreesWithSimOnEveryExample) {
  int n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(PLC_CELL_SOURCE_DIR) + "/examples")) {
    if (e.path().extension() != ".yaml") continue;
    expect_check_agrees_with_sim(e.path().string(), e.path().string());
    ++n;
  }
  EXPECT_GE(n, 15);  // every folder of examples/ holds cells
  // A cell of examples/ that sim runs is accepted by check.
  const Result ok = tool("check --config " + kDemo);
  EXPECT_EQ(ok.status, 0) << ok.out;
  EXPECT_EQ(ok.out, kDemo + ": OK, cell conveyor_demo\n" + std::string(PLC_CELL_SOURCE_DIR) +
                        "/examples/conveyor/conveyor.il: OK, 27 instructions, 0 labels\n");
}

// Rejections from every section: check and sim give the same status and the same lines.
TEST(CheckConfig, AgreesWithSimOnBadCells) {
  const Rejection bad[] = {
      {"top_key", "bogus: 1\n", ":2:1: error: key 'bogus': unknown key"},
      {"cell_key", "plc: {}\ncell2: {}\n", ":3:1: error: key 'cell2': unknown key"},
      {"plc_key", "plc: {scan_perod: 0.001}\n", ":2:7: error: key 'plc.scan_perod': unknown key"},
      {"plc_range", "plc: {scan_period: 0}\n", ":2:20: error: key 'plc.scan_period': value 0 out of range"},
      {"timer_base", "plc: {timer_bases: {T0-T9: 0.5}}\n", "a timer base is 0.01, 0.1 or 1 s"},
      {"retentive", "plc: {retentive: [M9-M1]}\n", ":2:19: error: key 'plc.retentive[0]': bad range 'M9-M1'"},
      {"signal_address", "signals: {a: Q1}\n", ":2:14: error: key 'signals.a': bad address 'Q1'"},
      {"signal_width", "signals: {a: R1}\n", ":2:14: error: key 'signals.a': a signal is a single discrete"},
      {"sim_key", "simulation: {outputs: {}}\n", ":2:14: error: key 'simulation.outputs': unknown key"},
      {"sim_input_key", "simulation: {inputs: {X1: {pules: {period: 1, width: 1}}}}\n",
       ":2:28: error: key 'simulation.inputs.X1.pules': unknown key"},
      {"sim_not_input", "simulation: {inputs: {Y1: {pulse: {period: 1, width: 1}}}}\n",
       ":2:23: error: key 'simulation.inputs.Y1': only inputs X0..X255 can be simulated"},
      {"sim_twice", "signals: {start: X1}\nsimulation:\n  inputs:\n    start: {steps: [[0, 1]]}\n"
                    "    X1: {steps: [[0, 0]]}\n",
       ":6:5: error: key 'simulation.inputs.X1': X1 is already driven by 'start' (line 5)"},
      {"sim_duration", "simulation: {inputs: {X1: {pulse: {period: fast, width: 1}}}}\n",
       ":2:44: error: key 'simulation.inputs.X1.pulse.period': expected a number"},
      {"sim_negative", "simulation: {inputs: {X1: {pulse: {period: 1, width: -1}}}}\n",
       "key 'simulation.inputs.X1.pulse.width': value -1 out of range"},
      {"counters_key", "counters: {hsc0: {mdoe: MD0}}\n", ":2:19: error: key 'counters.hsc0.mdoe': unknown key"},
      {"counters_x", "counters: {hsc6: {mode: MD0, a: X99}}\n", "key 'counters.hsc6.a'"},
      {"axes_key", "axes: {pso4: {}}\n", ":2:8: error: key 'axes.pso4': expected pso0, pso1, pso2, pso3, gp0 or gp1"},
      {"axes_table", "axes:\n  pso0:\n    table: {at: R0, text: \"001 SPD 100\\n    DRV ADR,+,10,Ut\\n    GOTO 7\\nMEND\\n\"}\n",
       "key 'axes.pso0.table.text'"},
      {"modules_key", "modules: {temprature: {}}\n", ":2:11: error: key 'modules.temprature': unknown key"},
      {"module_sensor", "modules:\n  temperature:\n    modules: [{type: 6RTD, sensor: K}]\n",
       "key 'modules.temperature.modules[0].sensor': an RTD module takes PT100 or PT1000"},
      {"module_generation", "modules: {generation: FX}\n",
       ":2:23: error: key 'modules.generation': FBs or FB"},
      {"analog_type", "modules: {analog: {modules: [{type: 9AD}]}}\n", "key 'modules.analog.modules[0].type'"},
      {"servers_key", "servers: {fatek: {tcpp: \"127.0.0.1:500\"}}\n",
       ":2:19: error: key 'servers.fatek.tcpp': unknown key"},
      {"server_port", "servers: {fatek: {tcp: \"127.0.0.1:70000\"}}\n",
       ":2:24: error: key 'servers.fatek.tcp': '127.0.0.1:70000': port '70000' is not 0..65535"},
      {"server_serial", "servers: {modbus: {rtu: \"/dev/ttyS9:9600:9Z1\"}}\n", "key 'servers.modbus.rtu'"},
      {"server_id", "servers: {modbus: {id: 300}}\n", ":2:24: error: key 'servers.modbus.id': value out of range [1, 247]"},
      {"server_timeout", "servers: {fatek: {idle_timeout: 5years}}\n",
       ":2:33: error: key 'servers.fatek.idle_timeout': expected a duration"},
      {"fatek_key", "fatek: {prots: {1: \"tcp:127.0.0.1:500\"}}\n", ":2:9: error: key 'fatek.prots': unknown key"},
      {"fatek_port", "fatek: {ports: {7: \"tcp:127.0.0.1:500\"}}\n",
       ":2:17: error: key 'fatek.ports.7': FUN151 port 7 outside 1..4"},
      {"fatek_line", "fatek: {ports: {1: \"/dev/ttyS1:9600:7X1\"}}\n", ":2:20: error: key 'fatek.ports.1': "},
      {"modbus_key", "modbus: {ports: {1: {tpc: \"127.0.0.1:502\"}}}\n",
       ":2:22: error: key 'modbus.ports.1.tpc': unknown key"},
      {"modbus_port", "modbus: {ports: {9: {tcp: \"127.0.0.1:502\"}}}\n",
       ":2:18: error: key 'modbus.ports.9': port 9 (FUN150 uses ports 1..4)"},
      {"counter_name", "counters: {hsc0: {mode: MD0, name: feed-1}}\n",
       ":2:36: error: key 'counters.hsc0.name': a counter name is letters, digits and _"},
      {"axis_name", "axes: {pso0: {name: x.axis}}\n", ":2:21: error: key 'axes.pso0.name': an axis name is letters"},
      {"channel_name", "modules: {temperature: {modules: [{type: 2TC, channels: [{name: oven zone}]}]}}\n",
       ":2:65: error: key 'modules.temperature.modules[0].channels[0].name': a temperature channel name is letters"},
      {"registers", "registers: [{name: a, points: [\"Q1\"]}]\n", "key 'registers"},
      {"yaml_syntax", "plc: [1, 2\n", "YAML syntax"},
  };
  for (const auto& c : bad) {
    const std::string path = write_cell(c.name, c.yaml);
    const Result check = tool("check --config " + path);
    EXPECT_EQ(check.status, 1) << c.name << "\n" << check.out;
    const std::string want = c.error[0] == ':' ? path + c.error : std::string(c.error);
    EXPECT_NE(check.out.find(want), std::string::npos) << c.name << ": want " << want << "\n" << check.out;
    EXPECT_EQ(check.out.rfind(path + ":", 0), 0u) << c.name << ": every error names the file\n" << check.out;
    expect_check_agrees_with_sim(path, c.name);
  }
}

// check builds and stops: FUN151's TCP port is read but not connected, where sim connects.
TEST(CheckConfig, OpensNoPort) {
  const int srv = ::socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(srv, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(srv, reinterpret_cast<sockaddr*>(&a), sizeof a), 0);
  socklen_t len = sizeof a;
  ASSERT_EQ(::getsockname(srv, reinterpret_cast<sockaddr*>(&a), &len), 0);
  ASSERT_EQ(::listen(srv, 4), 0);
  const std::string path =
      write_cell("port", "fatek: {ports: {1: \"tcp:127.0.0.1:" + std::to_string(ntohs(a.sin_port)) + "\"}}\n");
  // A finished process's connect() is already in the listen queue: poll without waiting.
  auto pending = [&] {
    pollfd p{srv, POLLIN, 0};
    return ::poll(&p, 1, 0) == 1;
  };
  const Result check = tool("check --config " + path);
  EXPECT_EQ(check.status, 0) << check.out;
  EXPECT_FALSE(pending()) << "check connected to the FUN151 port";
  const Result sim = tool("sim --config " + path + " --duration 1ms");
  EXPECT_EQ(sim.status, 0) << sim.out;
  EXPECT_TRUE(pending()) << "sim did not open the port: the control of this test is void";
  ::close(srv);
}

// ---- check and sim warn about operands the FUNs refuse at run time ----------------------

// The PLC accepts these operands and turns the FUN's ERR on when it runs; check says so at
// the line beforehand and passes, sim says so at load and runs.
TEST(CheckWarnings, ConstantOperandsTheFunRefusesAtRunTime) {
  const std::string yaml = kCheckDir + "fb_warn.yaml";
  std::ofstream(yaml) << "cell: {program: plc_cell_check_fb_warn.il}\nmodules: {generation: FB}\n";
  const std::string prog = kCheckDir + "fb_warn.il";
  std::ofstream(prog) << "ORG M3\nLD M1925\n"                                               // 1, 2
                         "FUN 73 Tp=4 Pl=0 Sm=0 Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sh=0 Zh=4 Sv=R100 Os=R120 PR=R140 "
                         "IR=R160 DR=R180 OR=R300 WR=R200 ERR=M10\n"                            // 3
                         "ORG M3\nLD M1925\n"                                               // 4, 5
                         "FUN 73 Tp=0 Pl=0 Sm=2 Ym=Y16 AR=R3842 TR=R0 Yh=Y48 Sh=0 Zh=0 Sv=R100 Os=R120 PR=R140 "
                         "IR=R160 DR=R180 OR=R300 WR=R200 ERR=M10\n"                            // 6
                         "ORG M4\nFUN 85 Tp=0 Pl=0 Zn=25 Yn=Y64 SR=R0 WR=R100 ERR=M1\n"       // 7, 8
                         "ORG M5\nFUN 85 Tp=0 Pl=0 Zn=24 Yn=Y64 SR=R0 WR=R100 ERR=M1\n"       // 9, 10
                         "END\n";
  const Result r = tool("check --config " + yaml);
  EXPECT_EQ(r.status, 0) << r.out;
  const std::string tail = ": at run time the PLC turns its ERR on and the instruction does nothing";
  for (const std::string& w : {
           prog + ":3:1: warning: FUN 73 TSTC: Tp=4: needs Tp 0 (K), 1 (J), 2 (PT-100) or 3 (PT-1000)" + tail,
           prog + ":6:1: warning: FUN 73 TSTC: Sm=2: needs 0 <= Sm <= 28, a multiple of 4" + tail,
           prog + ":6:1: warning: FUN 73 TSTC: Zh=0: needs 1 <= Zh <= 32 and Sh + Zh <= 32" + tail,
           prog + ":8:1: warning: FUN 85 TPSNS: Zn=25: needs 1 <= Zn <= 24" + tail,
           prog + ":10:1: warning: FUN 85 TPSNS: may be used once in a program, this is use 2 (the first at line 8)" + tail,
           std::string("5 warning(s)\n")})
    EXPECT_NE(r.out.find(w), std::string::npos) << w << "\n" << r.out;
  EXPECT_NE(r.out.find(prog + ": OK"), std::string::npos) << r.out;
  // sim: the same lines at load, and the run goes on.
  const Result sim = tool("sim --config " + yaml + " --duration 10ms");
  EXPECT_EQ(sim.status, 0) << sim.out;
  EXPECT_NE(sim.out.find(prog + ":8:1: warning: FUN 85 TPSNS: Zn=25"), std::string::npos) << sim.out;
  // A program without such operands gets no warning.
  const Result ok = tool("check --program " + std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.il");
  EXPECT_EQ(ok.out.find("warning"), std::string::npos) << ok.out;
}
