#pragma once
// Recordings made the way users make them: `plc_cell sim --record` on the demo conveyor,
// and the same run again in process for the values a recording must give back.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <sstream>
#include <string>

#include "../core/run_tool.h"
#include "plc_cell/recording/image.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {
namespace testing {

inline const std::string kExamples = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/";

// A folder of its own for a test's files.
inline std::string scratch_dir(const std::string& name) {
  const std::string dir = "/tmp/plc_cell_recording_" + std::to_string(getpid()) + "_" + name;
  EXPECT_EQ(run_shell("rm -rf " + dir + " && mkdir -p " + dir).status, 0);
  return dir;
}

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// The demo cell with its real-time clock started at a fixed date: without one the RTC
// registers start from the host's clock, and two runs a second apart differ there.
inline std::string fixed_clock_conveyor() {
  const std::string dir = "/tmp/plc_cell_recording_" + std::to_string(getpid()) + "_cell";
  ::mkdir(dir.c_str(), 0755);
  std::string yaml = file_bytes(kExamples + "conveyor.yaml");
  const std::string program = "program: conveyor.il";
  yaml.replace(yaml.find(program), program.size(), "program: " + kExamples + "conveyor.il");
  std::ofstream(dir + "/conveyor.yaml") << yaml << "modules:\n  rtc: {start: 2026-01-01T00:00:00}\n";
  std::string scenario = file_bytes(kExamples + "too_strict.fails.yaml");
  const std::string cell = "cell: conveyor.yaml";
  scenario.replace(scenario.find(cell), cell.size(), "cell: " + dir + "/conveyor.yaml");
  std::ofstream(dir + "/too_strict.fails.yaml") << scenario;
  return dir + "/conveyor.yaml";
}
inline const std::string kConveyorYaml = fixed_clock_conveyor();
// too_strict.fails.yaml on that cell.
inline const std::string kFailingScenario = kConveyorYaml.substr(0, kConveyorYaml.rfind('/')) + "/too_strict.fails.yaml";

// `plc_cell sim --record` of the demo conveyor for duration; returns the file's path.
inline std::string record_conveyor(const std::string& dir, const std::string& duration, const std::string& name = "run") {
  const std::string path = dir + "/" + name + ".plcrec";
  const auto r = run_tool("sim --config " + kConveyorYaml + " --duration " + duration + " --record " + path);
  EXPECT_EQ(r.status, 0) << r.out;
  return path;
}

// A fresh in-process run of the demo, scanned in virtual time as plc_cell sim scans it.
struct ConveyorRun {
  Cell cell{kConveyorYaml, CellOverrides{}, Cell::Purpose::Simulate};
  VirtualRun run{cell.plc(), cell.scan_period_us()};
  ConveyorRun() { EXPECT_TRUE(cell.plc().set_mode(RunMode::Run)); }
  // Scans up to and including the scan at t_us; the memory then.
  recording::Image image_after(uint64_t t_us) {
    while (run.now_us() <= t_us) run.run_for(cell.scan_period_us());
    recording::Image img;
    cell.plc().locked([&](ScanEngine&, Memory& m) {
      recording::capture(m, &img);
      return 0;
    });
    return img;
  }
};

}  // namespace testing
}  // namespace plc_cell
