// The cell YAML's `ports:` section and its older spellings in `fatek:` and `modbus:`:
// every error names file:line:column, the key and why, all of them in one run, and a
// port declared twice must be one line.
#include <gtest/gtest.h>

#include <fstream>

#include "plc_cell/comm/port_config.h"
#include "plc_cell/comm/protocol_functions.h"
#include "plc_cell/core/error.h"
#include "plc_cell/sim/soft_cell.h"

using namespace plc_cell;

namespace {

std::string errors_of(const std::string& yaml) {
  try {
    read_port_settings(YAML::Load(yaml), "cell.yaml");
  } catch (const SourceError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(PortConfig, ReadsEachPortsLineAndTheTimeout) {
  const PortSettings s = read_port_settings(
      YAML::Load("ports:\n  timeout: 250ms\n  1: {serial: /dev/ttyS1}\n  2: {tcp: 10.0.0.5:502}\n"
                 "  3: {serial: /dev/ttyUSB0:19200:8N1}\n"),
      "cell.yaml");
  EXPECT_EQ(s.timeout_ms, 250);
  ASSERT_EQ(s.lines.size(), 3u);
  EXPECT_EQ(s.lines.at(1).to_string(), "/dev/ttyS1:9600:7E1");  // the FBs port's factory setting
  EXPECT_EQ(s.lines.at(2).to_string(), "tcp:10.0.0.5:502");
  EXPECT_EQ(s.lines.at(3).to_string(), "/dev/ttyUSB0:19200:8N1");
  EXPECT_EQ(read_port_settings(YAML::Load("cell: {}"), "cell.yaml").lines.size(), 0u);
  EXPECT_EQ(read_port_settings(YAML::Load("cell: {}"), "cell.yaml").timeout_ms, 500);
}

TEST(PortConfig, TheOlderSpellingsFeedTheSamePorts) {
  const PortSettings s = read_port_settings(
      YAML::Load("fatek:\n  timeout_ms: 300\n  ports:\n    1: /dev/ttyS1:9600:7E1\n    2: tcp:127.0.0.1:500\n"
                 "modbus:\n  ports:\n    3: {rtu: /dev/ttyUSB0}\n"),
      "cell.yaml");
  EXPECT_EQ(s.timeout_ms, 300);
  EXPECT_EQ(s.lines.at(1).to_string(), "/dev/ttyS1:9600:7E1");
  EXPECT_EQ(s.lines.at(2).to_string(), "tcp:127.0.0.1:500");
  EXPECT_EQ(s.lines.at(3).to_string(), "/dev/ttyUSB0:9600:8E1");  // Modbus RTU's default framing
}

TEST(PortConfig, ErrorsNameFileLineKeyAndWhy) {
  EXPECT_EQ(errors_of("ports:\n  1: {serail: /dev/ttyS1}\n"),
            "cell.yaml:2:7: error: key 'ports.1.serail': unknown key (expected one of: serial, tcp)");
  EXPECT_EQ(errors_of("ports:\n  timout: 1s\n"),
            "cell.yaml:2:3: error: key 'ports.timout': unknown key (expected a port 1..4 or timeout)");
  EXPECT_EQ(errors_of("ports:\n  5: {tcp: 10.0.0.5:502}\n"),
            "cell.yaml:2:3: error: key 'ports.5': port 5 outside 1..4 (COM ports 1..4)");
  EXPECT_EQ(errors_of("ports:\n  0: {tcp: 10.0.0.5:502}\n"),
            "cell.yaml:2:3: error: key 'ports.0': port 0 outside 1..4 (COM ports 1..4)");
  EXPECT_EQ(errors_of("ports:\n  1: {serial: /dev/ttyS1:9600:7X1}\n").rfind("cell.yaml:2:15: error: key 'ports.1.serial': ", 0), 0u);
  EXPECT_EQ(errors_of("ports:\n  1: {tcp: 10.0.0.5}\n").rfind("cell.yaml:2:12: error: key 'ports.1.tcp': ", 0), 0u);
  EXPECT_EQ(errors_of("ports:\n  1: {serial: /dev/ttyS1, tcp: 10.0.0.5:502}\n"),
            "cell.yaml:2:6: error: key 'ports.1': give one of serial or tcp");
  EXPECT_EQ(errors_of("ports:\n  timeout: 0ms\n").rfind("cell.yaml:2:12: error: key 'ports.timeout': ", 0), 0u);
  EXPECT_EQ(errors_of("ports: [1, 2]\n").rfind("cell.yaml:1:8: error: key 'ports': expected a mapping", 0), 0u);
}

TEST(PortConfig, EveryErrorOfTheSectionInOneRun) {
  const std::string e = errors_of("ports:\n  1: {serail: /dev/ttyS1}\n  7: {tcp: a:1}\n  2: {serial: /dev/ttyS2:12:7E1}\n");
  EXPECT_NE(e.find("cell.yaml:2:7: error: key 'ports.1.serail'"), std::string::npos) << e;
  EXPECT_NE(e.find("cell.yaml:3:3: error: key 'ports.7'"), std::string::npos) << e;
  EXPECT_NE(e.find("cell.yaml:4:15: error: key 'ports.2.serial'"), std::string::npos) << e;
}

TEST(PortConfig, APortDeclaredTwiceMustBeOneLine) {
  // The same line in both places is one port, used by FUN150 and FUN151 alike.
  const PortSettings same = read_port_settings(
      YAML::Load("ports:\n  1: {serial: /dev/ttyS1:9600:8E1}\nmodbus:\n  ports:\n    1: {rtu: /dev/ttyS1:9600:8E1}\n"
                 "fatek:\n  ports:\n    1: /dev/ttyS1:9600:8E1\n"),
      "cell.yaml");
  EXPECT_EQ(same.lines.size(), 1u);
  EXPECT_EQ(errors_of("ports:\n  1: {serial: /dev/ttyS1:9600:7E1}\nmodbus:\n  ports:\n    1: {rtu: /dev/ttyS1}\n"),
            "cell.yaml:5:5: error: key 'modbus.ports.1': port 1 is /dev/ttyS1:9600:8E1 here but /dev/ttyS1:9600:7E1 "
            "at line 2 (ports.1): a port is one line, used by FUN150 and FUN151 alike");
  EXPECT_EQ(errors_of("fatek:\n  ports:\n    2: tcp:10.0.0.5:500\nmodbus:\n  ports:\n    2: {tcp: 10.0.0.5:502}\n"),
            "cell.yaml:6:5: error: key 'modbus.ports.2': port 2 is tcp:10.0.0.5:502 here but tcp:10.0.0.5:500 "
            "at line 3 (fatek.ports.2): a port is one line, used by FUN150 and FUN151 alike");
  EXPECT_EQ(errors_of("ports:\n  timeout: 1s\nfatek:\n  timeout_ms: 100\n"),
            "cell.yaml:4:15: error: key 'fatek.timeout_ms': the time-out is also given as ports.timeout "
            "(write it once, as ports.timeout)");
}

TEST(PortConfig, TheCellNamesItsFileAndCheckReadsItAlike) {
  const std::string prog = "/tmp/plc_cell_port_config_end.il";
  std::ofstream(prog) << "END\n";
  const std::string cfg = "/tmp/plc_cell_port_config_bad.yaml";
  std::ofstream(cfg) << "cell: {program: " << prog << "}\nports:\n  9: {tcp: 127.0.0.1:1}\n";
  std::string errors[2];
  for (const bool open_ports : {true, false}) {
    CellExtensions x;
    x.push_back(std::make_unique<ProtocolFunctions>(open_ports));
    try {
      SoftCell cell(cfg, "", std::move(x));
      ADD_FAILURE() << "accepted";
    } catch (const SourceError& e) {
      errors[open_ports] = e.what();
    }
  }
  EXPECT_EQ(errors[1].rfind(cfg + ":3:3: error: key 'ports.9': port 9 outside 1..4", 0), 0u) << errors[1];
  EXPECT_EQ(errors[0], errors[1]);
}
