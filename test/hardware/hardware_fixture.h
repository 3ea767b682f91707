#pragma once
// `plc_cell run` standing in for a real PLC, `plc_cell test --target` run against it, and the
// stand-in's state as a FATEK master reads it (every forced point of a range, the values of
// the points a scenario touches), for the tests that the PLC is left as it was found.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <string>
#include <vector>

#include "../harness/child_process.h"
#include "../reliability/run_child.h"
#include "../reliability/temp_dir.h"
#include "plc_cell/fatek/client.h"

namespace hardware_test {

const std::string kSource = PLC_CELL_SOURCE_DIR;
const std::string kConveyor = kSource + "/examples/conveyor/conveyor.yaml";
const std::string kConveyorScenario = kSource + "/examples/conveyor/conveyor.hardware.scenario.yaml";
const std::string kDemoScenario = kSource + "/examples/conveyor/conveyor.scenario.yaml";
const std::string kRelayCell = kSource + "/test/hardware/relay_cell.yaml";
const std::string kRelayScenario = kSource + "/test/hardware/relay.scenario.yaml";

// The port of the stand-in's server of this kind ("FATEK TCP", "TRi TCP", "Modbus TCP").
inline int port_of(const RunChild& c, const std::string& kind) {
  const auto at = c.log.find("serving " + kind + " 127.0.0.1:");
  if (at == std::string::npos) throw std::runtime_error("no " + kind + " server in: " + c.log);
  return std::stoi(c.log.substr(at + std::string("serving " + kind + " 127.0.0.1:").size()));
}

// Until the stand-in scans: every server it was given is up by then.
inline void wait_scanning(RunChild& c) {
  for (std::string line; c.next_line(&line);)
    if (line.find("scanning every") != std::string::npos) return;
  throw std::runtime_error("plc_cell run did not start scanning: " + c.log);
}

inline std::string loopback(int port) { return "127.0.0.1:" + std::to_string(port); }

// The stand-in as a FATEK master sees it.
struct PlcState {
  std::vector<bool> forced;      // X0-X31, Y0-Y31, M0-M63
  std::vector<uint32_t> values;  // of the addresses asked for
  bool run = false;

  bool operator==(const PlcState& o) const { return forced == o.forced && values == o.values && run == o.run; }
};

inline std::vector<plc_cell::Address> addresses(const std::vector<std::string>& names) {
  std::vector<plc_cell::Address> out;
  for (const auto& n : names) out.push_back(plc_cell::parse_address(n));
  return out;
}

inline PlcState state_of(int fatek_port, const std::vector<std::string>& values_of) {
  plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport(loopback(fatek_port)));
  PlcState s;
  for (const char* area : {"X0", "Y0"}) {
    const auto d = c.read_disabled(plc_cell::parse_address(area), 32);
    s.forced.insert(s.forced.end(), d.begin(), d.end());
  }
  const auto m = c.read_disabled(plc_cell::parse_address("M0"), 64);
  s.forced.insert(s.forced.end(), m.begin(), m.end());
  if (!values_of.empty()) s.values = c.read_mixed(addresses(values_of));
  s.run = c.status().run;
  return s;
}

inline std::string describe(const PlcState& s, const std::vector<std::string>& names) {
  std::string out = s.run ? "RUN; forced:" : "STOP; forced:";
  static const char* areas[] = {"X", "Y", "M"};
  for (size_t i = 0; i < s.forced.size(); ++i)
    if (s.forced[i]) out += std::string(" ") + areas[i < 32 ? 0 : i < 64 ? 1 : 2] + std::to_string(i < 64 ? i % 32 : i - 64);
  out += "; values:";
  for (size_t i = 0; i < s.values.size() && i < names.size(); ++i) out += " " + names[i] + "=" + std::to_string(s.values[i]);
  return out;
}

// Each test's restore journals in a folder of its own.
class HardwareTest : public ::testing::Test {
 protected:
  HardwareTest() { ::setenv("XDG_STATE_HOME", state_.path().c_str(), 1); }
  ~HardwareTest() override { ::unsetenv("XDG_STATE_HOME"); }
  const std::string& state_dir() const { return state_.path(); }
  const std::string& temp() const { return temp_.path(); }

  // plc_cell test ARGS..., to its end (at most limit_s).
  static plc_cell::testing::ToolResult test_tool(std::vector<std::string> args, int limit_s = 120) {
    args.insert(args.begin(), {PLC_CELL_TOOL, "test"});
    return plc_cell::testing::run_process(args, limit_s);
  }

 private:
  TempDir state_, temp_;
};

}  // namespace hardware_test
