#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/apply_config.h"
#include "plc_cell/sim/simulated_cell.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/sim/virtual_run.h"

using namespace plc_cell;

namespace {
std::string error_of(const std::string& yaml) {
  try {
    parse_cell_config(yaml, "cell.yaml", Cell::sections());
  } catch (const SourceError& e) {
    return e.what();
  }
  return "";
}
}  // namespace

TEST(CellConfig, ReadsEveryKey) {
  const CellConfig c = parse_cell_config(
      "cell: {name: line3, program: prog.il}\n"
      "plc:\n"
      "  scan_period: 0.002\n"
      "  watchdog: 0.05\n"
      "  retentive: [M800-M999, D0-D99, R7]\n"
      "  timer_bases: {T0-T9: 1, T10-T19: 0.1}\n"
      "signals:\n"
      "  part_present: X3\n"
      "  conveyor_run: Y0\n"
      "simulation:\n"
      "  inputs:\n"
      "    part_present: {pulse: {period: 2, width: 0.5, delay: 1}}\n"
      "    X5: {steps: [[0, 1], [1.5, 0]]}\n"
      "    X6: {follow: {source: conveyor_run, on_delay: 0.2}}\n",
      "/cells/line3.yaml", Cell::sections());
  EXPECT_EQ(c.name, "line3");
  EXPECT_EQ(c.program, "/cells/prog.il");  // relative to the config's folder
  EXPECT_EQ(c.scan_period_us, 2000u);
  EXPECT_EQ(c.watchdog_us, 50000u);
  ASSERT_EQ(c.retentive.size(), 3u);
  EXPECT_EQ(c.retentive[1].area, Area::D);
  EXPECT_EQ(c.retentive[1].last, 99u);
  EXPECT_EQ(c.retentive[2].first, 7u);
  ASSERT_EQ(c.timer_bases.size(), 2u);
  EXPECT_EQ(c.timer_bases[0].base_us, 1000000u);
  ASSERT_EQ(c.signals.size(), 2u);
  EXPECT_EQ(c.resolve("part_present"), parse_address("X3"));
  EXPECT_EQ(c.resolve("R5"), parse_address("R5"));
  ASSERT_EQ(c.sim_inputs.size(), 3u);
  EXPECT_EQ(c.sim_inputs[0].x, 3u);
  EXPECT_EQ(c.sim_inputs[0].period_us, 2000000u);
  EXPECT_EQ(c.sim_inputs[1].steps.size(), 2u);
  EXPECT_EQ(c.sim_inputs[2].source, parse_address("Y0"));
  EXPECT_EQ(c.sim_inputs[2].on_delay_us, 200000u);
}

TEST(CellConfig, EngineIsOneOfThreeAndNativeByDefault) {
  EXPECT_EQ(parse_cell_config("cell: {name: a}\n", "cell.yaml", Cell::sections()).engine, EngineChoice::Native);
  EXPECT_EQ(parse_cell_config("plc: {engine: interpreter}\n", "cell.yaml", Cell::sections()).engine,
            EngineChoice::Interpreter);
  EXPECT_NE(error_of("plc:\n  engine: jit\n").find("cell.yaml:2:11: error: key 'plc.engine': expected native, interpreter or lockstep"),
            std::string::npos) << error_of("plc:\n  engine: jit\n");
}

TEST(CellConfig, ErrorsNameFileLineAndKey) {
  EXPECT_EQ(error_of("plc:\n  scan_perod: 0.001\n"),
            "cell.yaml:2:3: error: key 'plc.scan_perod': unknown key (expected one of: engine, persist, retentive, "
            "scan_period, timer_bases, watchdog)");
  EXPECT_NE(error_of("signals:\n  a: Q1\n").find("cell.yaml:2:6: error: key 'signals.a': bad address 'Q1'"),
            std::string::npos);
  EXPECT_NE(error_of("signals:\n  a: R1\n").find("a signal is a single discrete"), std::string::npos);
  EXPECT_NE(error_of("signals:\n  my-signal: X1\n").find("becomes a ROS topic name"), std::string::npos);
  EXPECT_NE(error_of("plc: {scan_period: 5}\n").find("out of range [0.0001, 1]"), std::string::npos);
  EXPECT_NE(error_of("plc: {scan_period: fast}\n").find("expected a number"), std::string::npos);
  EXPECT_NE(error_of("plc: {retentive: [M9-M1]}\n").find("low end first"), std::string::npos);
  EXPECT_NE(error_of("plc: {retentive: [M1-D9]}\n").find("same area"), std::string::npos);
  EXPECT_NE(error_of("plc: {timer_bases: {T0-T9: 0.5}}\n").find("0.01, 0.1 or 1 s"), std::string::npos);
  EXPECT_NE(error_of("simulation: {inputs: {Y1: {pulse: {period: 1, width: 1}}}}\n").find("only inputs X0..X255"),
            std::string::npos);
  EXPECT_NE(error_of("simulation: {inputs: {nobody: {pulse: {period: 1, width: 1}}}}\n")
                .find("'nobody' is neither a signal of cell cell nor an address"),
            std::string::npos);
  EXPECT_NE(error_of("simulation: {inputs: {X1: {pulse: {period: 1, width: 2}}}}\n").find("longer than the period"),
            std::string::npos);
  EXPECT_NE(error_of("simulation: {inputs: {X1: {steps: [[1, 1], [0.5, 0]]}}}\n").find("must not decrease"),
            std::string::npos);
  EXPECT_NE(error_of("cell: [1, 2\n").find("cell.yaml:"), std::string::npos);
  EXPECT_NE(error_of("cell: [1, 2\n").find("YAML syntax"), std::string::npos);
  EXPECT_NE(error_of("bogus: 1\n").find("key 'bogus': unknown key"), std::string::npos);
  // YAML is Unicode text: other bytes are refused where they are, as a syntax error is.
  EXPECT_EQ(error_of("cell: {name: t}\nsignals: {caf\xE9: X1}\n"),
            "cell.yaml:2:14: error: not UTF-8: byte 0xE9 (a YAML file is Unicode text, read as UTF-8)");
  EXPECT_EQ(error_of("cell: {name: \"a\x02\"}\n").rfind("cell.yaml:1:16: error: character U+0002 is not allowed", 0), 0u);
}

// The reader every YAML file of plc_cell goes through (cell, fatek_bridge, modbus_bridge).
TEST(YamlReader, FilesAndValueParsersReportTheirLine) {
  const std::string path = "/tmp/plc_cell_yaml_reader_test.yaml";
  std::ofstream(path) << "signals:\n  a: X1\ngroups: [\n";
  try {
    YamlReader::load_file(path);
    FAIL() << "no error";
  } catch (const SourceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("YAML syntax"), std::string::npos) << e.what();
  }
  std::ofstream(path) << "signals:\n  a: X1\n";
  EXPECT_EQ(YamlReader::load_file(path)["signals"]["a"].as<std::string>(), "X1");
  EXPECT_THROW(YamlReader::load_file("/nonexistent/plc_cell.yaml"), Error);

  const YamlReader r("cell.yaml");
  const YAML::Node doc = r.load("line:\n  tcp: 'localhost'\n  rtu: /dev/ttyS1:9600:9Z1\n  n: 9\n  on: fast\n");
  const auto error = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const SourceError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error([&] { r.host_port(doc["line"]["tcp"], "line.tcp"); }),
            "cell.yaml:2:8: error: key 'line.tcp': 'localhost': expected HOST:PORT, e.g. 127.0.0.1:500");
  EXPECT_EQ(error([&] { r.serial_line(doc["line"]["rtu"], "line.rtu", "8E1"); }).rfind("cell.yaml:3:8: error: key 'line.rtu': ", 0), 0u);
  EXPECT_EQ(error([&] { r.integer(doc["line"]["n"], "line.n", 1, 4); }), "cell.yaml:4:6: error: key 'line.n': value out of range [1, 4]");
  EXPECT_EQ(error([&] { r.choice(doc["line"]["on"], "line.on", {"slow", "normal"}); }),
            "cell.yaml:5:7: error: key 'line.on': expected one of: normal, slow");
  EXPECT_EQ(r.serial_line(YAML::Load("/dev/ttyS1:19200"), "k", "8E1"), "/dev/ttyS1:19200");
  EXPECT_EQ(r.host_port(YAML::Load("127.0.0.1:502"), "k"), "127.0.0.1:502");
}

// yaml-cpp stops at 500 levels of nesting and calls it "bad file": the error says what it
// is and the limit, at the line where the reader stopped, in the file and in text alike.
TEST(YamlReader, TooDeepNestingSaysSoWithTheLimit) {
  const std::string why =
      "YAML syntax: nesting too deep: more than 499 levels of mappings and lists inside each other "
      "(the reader's limit)";
  std::string block = "cell: {name: t}\nsignals:\n";
  for (int i = 1; i < 600; ++i) block += std::string(static_cast<size_t>(i), ' ') + "k:\n";
  const std::string e = error_of(block);
  EXPECT_EQ(e.rfind("cell.yaml:", 0), 0u) << e;
  EXPECT_NE(e.find(why), std::string::npos) << e;
  EXPECT_EQ(e.find("bad file"), std::string::npos) << e;
  const std::string flow = "cell: {name: t}\nregisters: " + std::string(600, '[') + std::string(600, ']') + "\n";
  EXPECT_EQ(error_of(flow).rfind("cell.yaml:2:", 0), 0u) << error_of(flow);
  EXPECT_NE(error_of(flow).find(why), std::string::npos) << error_of(flow);
  // 499 levels are read (and then refused for what they mean, not for their depth).
  const std::string ok = "registers: " + std::string(498, '[') + std::string(498, ']') + "\n";
  EXPECT_EQ(error_of(ok).find("nesting too deep"), std::string::npos) << error_of(ok);

  const std::string path = ::testing::TempDir() + "/plc_cell_deep.yaml";
  std::ofstream(path) << flow;
  try {
    YamlReader::load_file(path);
    FAIL() << "no error";
  } catch (const SourceError& x) {
    EXPECT_EQ(std::string(x.what()).rfind(path + ":2:", 0), 0u) << x.what();
    EXPECT_NE(std::string(x.what()).find(why), std::string::npos) << x.what();
  }
}

// ~registers/<group> of plc_node (and fatek_bridge's groups): same YAML, same checks.
TEST(CellConfig, RegisterGroups) {
  const CellConfig c = parse_cell_config(
      "registers:\n"
      "  - {name: levels, rate: 5, points: ['R100:10', DR200, 'X0:16']}\n"
      "  - {name: axis0, points: [DR4088]}\n",
      "cell.yaml", Cell::sections());
  ASSERT_EQ(c.registers.size(), 2u);
  EXPECT_EQ(c.registers[0].name, "levels");
  EXPECT_EQ(c.registers[0].rate_hz, 5.0);
  EXPECT_EQ(c.registers[0].text, "R100:10,DR200,X0:16");
  ASSERT_EQ(c.registers[0].spans.size(), 3u);
  EXPECT_EQ(c.registers[0].spans[0].start, parse_address("R100"));
  EXPECT_EQ(c.registers[0].spans[0].count, 10u);
  EXPECT_EQ(c.registers[0].spans[2].count, 16u);
  EXPECT_EQ(c.registers[1].rate_hz, 1.0);  // the default

  EXPECT_EQ(error_of("registers:\n  - {name: a, points: ['R8070:5']}\n"),
            "cell.yaml:2:24: error: key 'registers[0].points[0]': address R8070 x 5: out of range: R has elements "
            "0..8071");
  EXPECT_NE(error_of("registers:\n  - {name: a, points: ['R1:x']}\n").find("bad count"), std::string::npos);
  EXPECT_NE(error_of("registers:\n  - {name: a, points: [Q1]}\n").find("'registers[0].points[0]': bad address"),
            std::string::npos);
  EXPECT_NE(error_of("registers:\n  - {name: a, points: []}\n").find("non-empty list"), std::string::npos);
  EXPECT_NE(error_of("registers:\n  - {name: a-b, points: [R1]}\n").find("becomes a ROS topic name"),
            std::string::npos);
  EXPECT_EQ(error_of("registers:\n  - {name: a, points: [R1]}\n  - {name: a, points: [R2]}\n"),
            "cell.yaml:3:12: error: key 'registers[1].name': group 'a' defined twice");
  EXPECT_NE(error_of("registers:\n  - {name: a, rate: 0, points: [R1]}\n").find("out of range [0.01, 100]"),
            std::string::npos);
  EXPECT_NE(error_of("registers:\n  - {name: a, every: 1, points: [R1]}\n").find("unknown key"),
            std::string::npos);
  EXPECT_NE(error_of("registers: {a: R1}\n").find("expected a list"), std::string::npos);
}

TEST(CellConfig, Durations) {
  EXPECT_EQ(parse_duration_us("2.5s"), 2500000u);
  EXPECT_EQ(parse_duration_us("100ms"), 100000u);
  EXPECT_EQ(parse_duration_us("250us"), 250u);
  EXPECT_EQ(parse_duration_us("3"), 3000000u);
  EXPECT_EQ(parse_duration_us("1min"), 60000000u);
  EXPECT_THROW(parse_duration_us("fast"), Error);
  EXPECT_THROW(parse_duration_us("5h"), Error);
  EXPECT_THROW(parse_duration_us("-1s"), Error);
}

TEST(SimulatedCell, SignalsDriveInputsInVirtualTime) {
  Plc plc;
  SimulatedCell sim(*plc.locked([](ScanEngine& e, Memory&) { return &e; }),
                    *plc.locked([](ScanEngine&, Memory& m) { return &m; }));
  const CellConfig c = parse_cell_config(
      "simulation:\n  inputs:\n"
      "    X0: {pulse: {period: 0.1, width: 0.03, delay: 0.05}}\n"
      "    X1: {steps: [[0.2, 1], [0.25, 0]]}\n"
      "    X2: {follow: {source: Y0, on_delay: 0.01, off_delay: 0.02}}\n",
      "", Cell::sections());
  apply_cell_config(c, plc, sim);
  plc.locked([&](ScanEngine& e, Memory&) {
    e.add_hook(&sim);
    return 0;
  });
  plc.load_program_text("ORG X1\nOUT Y0\nEND\n", "t.il");
  plc.set_mode(RunMode::Run);
  VirtualRun run(plc, 1000);
  run.watch(parse_address("X0"));
  run.watch(parse_address("X1"));
  run.watch(parse_address("X2"));
  std::vector<std::string> log;
  run.run_for(400000, [&](const WatchChange& ch) {
    log.push_back(std::to_string(ch.t_us / 1000) + ":X" + std::to_string(ch.watch) + "=" + std::to_string(ch.value));
  });
  // X0 on [50,80) [150,180) ...; X1 on [200,250); Y0 follows X1; X2 on 10 ms after Y0 was
  // seen (scan 201) and off 20 ms after Y0 dropped (seen at 251).
  const std::vector<std::string> want = {"0:X0=0",   "0:X1=0",   "0:X2=0",   "50:X0=1",  "80:X0=0",
                                         "150:X0=1", "180:X0=0", "200:X1=1", "211:X2=1", "250:X0=1",
                                         "250:X1=0", "271:X2=0", "280:X0=0", "350:X0=1", "380:X0=0"};
  EXPECT_EQ(log, want);
}

TEST(SoftCell, TheDemoCellRuns) {
  SoftCell cell(std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/conveyor.yaml", "");
  Plc& plc = cell.plc();
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  VirtualRun run(plc, 1000);
  run.watch(cell.config().resolve("conveyor_run"));
  run.watch(parse_address("R0"));
  std::vector<uint64_t> conveyor_changes;
  run.run_for(11000000, [&](const WatchChange& ch) {
    if (ch.watch == 0) conveyor_changes.push_back(ch.t_us);
  });
  // A part every 5 s from t = 1 s: the conveyor stops at 1 s, the robot has 1.5 s, the
  // stopper lowers at 2.5 s and the conveyor restarts one scan later; again at 6 s.
  const std::vector<uint64_t> want = {0, 1000000, 2501000, 6000000, 7501000};
  EXPECT_EQ(conveyor_changes, want);
  EXPECT_EQ(run.values()[1], 2u);  // two parts done
}

TEST(SoftCell, ErrorsComeWithTheFileName) {
  try {
    SoftCell cell("", "");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("no program"), std::string::npos);
  }
  EXPECT_THROW(SoftCell("/nonexistent.yaml", ""), SourceError);
}

// A file that cannot be opened: the system's reason and the absolute path it was looked
// for at, and, when the cell YAML named it, that key's line (a relative program is taken
// from the YAML's folder, a relative config from the working directory).
TEST(SoftCell, AFileThatCannotBeOpenedNamesTheLineThatNamedItAndWhereItLooked) {
  const std::string dir = (std::filesystem::path(::testing::TempDir()) / "missing_files").string();
  ASSERT_EQ(std::system(("rm -rf " + dir + " && mkdir -p " + dir).c_str()), 0);
  const std::string cwd = std::filesystem::current_path().string();
  auto first_error = [](const std::string& config, const std::string& program) {
    try {
      SoftCell cell(config, program);
    } catch (const SourceError& e) {
      return e.diagnostics().at(0).to_string();
    }
    return std::string("no error");
  };
  std::ofstream(dir + "/cell.yaml") << "cell: {name: t,\n       program: progs/missing.il}\n";
  EXPECT_EQ(first_error(dir + "/cell.yaml", ""),
            dir + "/cell.yaml:2:17: error: key 'cell.program': cannot open the program file: No such file or "
                  "directory (looked for " + dir + "/progs/missing.il)");
  // --program, or ~program: no line named it; its own path and where it led.
  EXPECT_EQ(first_error(dir + "/cell.yaml", "rel/none.il"),
            "rel/none.il: error: cannot open the program file: No such file or directory (looked for " + cwd +
                "/rel/none.il)");
  EXPECT_EQ(first_error("nowhere/cell.yaml", ""),
            "nowhere/cell.yaml: error: cannot open the cell config: No such file or directory (looked for " + cwd +
                "/nowhere/cell.yaml)");
  // A folder is not a program.
  ASSERT_EQ(std::system(("mkdir -p " + dir + "/progs/missing.il").c_str()), 0);
  EXPECT_NE(first_error(dir + "/cell.yaml", "").find(dir + "/cell.yaml:2:17: error: key 'cell.program': cannot open "
                                                           "the program file: it is a directory"),
            std::string::npos);
}

TEST(CellConfig, TheTemplateParses) {
  const CellConfig c = load_cell_config(std::string(PLC_CELL_SOURCE_DIR) + "/config/cell_template.yaml", Cell::sections());
  EXPECT_EQ(c.name, "my_cell");
  EXPECT_EQ(c.signals.size(), 2u);
  EXPECT_EQ(c.sim_inputs.size(), 3u);
  EXPECT_EQ(c.retentive.size(), CellConfig::default_retentive().size());
  EXPECT_EQ(c.timer_bases.size(), 3u);
}

// A section in error does not hide the next: every error of the file, in file order.
TEST(CellConfig, ListsEveryErrorOfTheFile) {
  try {
    parse_cell_config(
        "cell: {nmae: x}\n"
        "plc: {scan_period: 5, watchdog: 99}\n"
        "signals: {a: Q1}\n"
        "simulation:\n"
        "  inputs:\n"
        "    X1: {pulse: {period: 1, width: 2}}\n"
        "    X2: {steps: [[0, 1]]}\n"
        "    X2: {steps: [[0, 0]]}\n"
        "bogus: 1\n",
        "cell.yaml", Cell::sections());
    FAIL() << "accepted";
  } catch (const SourceError& e) {
    std::vector<std::string> got;
    for (const auto& d : e.diagnostics()) got.push_back(d.to_string().substr(0, d.to_string().find(" error:")));
    const std::vector<std::string> want = {"cell.yaml:1:8:", "cell.yaml:2:20:", "cell.yaml:2:33:", "cell.yaml:3:14:",
                                           "cell.yaml:6:36:", "cell.yaml:8:5:", "cell.yaml:9:1:"};
    EXPECT_EQ(got, want) << e.what();
    EXPECT_NE(std::string(e.what()).find("key 'simulation.inputs.X2': X2 is already driven by 'X2' (line 7)"),
              std::string::npos)
        << e.what();
  }
}

// A cell is built reading the subsystems' sections after a failed one, the servers' with
// them, and the program after them.
TEST(CellBuild, ReportsEverySectionAndTheProgram) {
  std::ofstream("/tmp/plc_cell_softcell_bad.il") << "ORG X0\nOUT Q1\nEND\n";
  std::ofstream("/tmp/plc_cell_softcell_bad.yaml")
      << "cell: {program: plc_cell_softcell_bad.il}\n"
         "plc: {watchdog: 99}\n"
         "counters: {hsc9: {}}\n"
         "axes: {pso7: {}}\n"
         "modules: {temperature: {modules: [{type: 7TC}]}}\n"
         "servers: {modbus: {id: 0}}\n";
  try {
    Cell cell("/tmp/plc_cell_softcell_bad.yaml", {}, Cell::Purpose::Check);
    FAIL() << "built";
  } catch (const SourceError& e) {
    const std::string w = e.what();
    ASSERT_EQ(e.diagnostics().size(), 6u) << w;
    const char* keys[] = {"plc.watchdog", "counters.hsc9", "axes.pso7", "modules.temperature.modules[0].type",
                          "servers.modbus.id"};
    for (size_t i = 0; i < 5; ++i) {
      EXPECT_EQ(e.diagnostics()[i].where.line, int(i) + 2) << w;
      EXPECT_NE(e.diagnostics()[i].message.find(std::string("key '") + keys[i] + "'"), std::string::npos) << w;
    }
    EXPECT_EQ(e.diagnostics()[5].where.file, "/tmp/plc_cell_softcell_bad.il");
    EXPECT_EQ(e.diagnostics()[5].where.line, 2);
  }
}
