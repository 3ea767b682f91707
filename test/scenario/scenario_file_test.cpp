// Reading scenario files: the structure docs/testing-your-cell.md documents, and every
// error of a file in one reading, each at its file:line:column with the key and why.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "plc_cell/config/error_list.h"
#include "plc_cell/core/error.h"
#include "plc_cell/scenario/scenario_file.h"
#include "scenario_fixture.h"

using namespace plc_cell;
using namespace plc_cell::scenario;

namespace {

std::vector<std::string> errors_of(const std::string& text) {
  try {
    parse_scenario(text, "/d/bad.yaml");
  } catch (const SourceError& e) {
    std::vector<std::string> out;
    for (const auto& d : e.diagnostics()) out.push_back(d.to_string());
    return out;
  }
  return {};
}

}  // namespace

TEST(ScenarioFile, CasesSetupAndParameters) {
  const Scenario sc = parse_scenario(
      "cell: cells/a.yaml\n"
      "program: b.il\n"
      "setup:\n"
      "  - set: {X0: on}\n"
      "cases:\n"
      "  - name: first\n"
      "    setup: [{write: {R0: 1}}]\n"
      "    steps:\n"
      "      - at: 2.5s\n"
      "        expect: Y0\n"
      "  - name: count\n"
      "    parameters:\n"
      "      - {n: 3, t: 1s}\n"
      "      - {n: 5, t: 2s}\n"
      "    steps:\n"
      "      - after: ${t}\n"
      "        expect: R0 == ${n}\n",
      "/d/s.yaml");
  EXPECT_EQ(sc.cell, "/d/cells/a.yaml");  // relative to the scenario's folder
  EXPECT_EQ(sc.program, "/d/b.il");
  ASSERT_EQ(sc.cases.size(), 3u);
  EXPECT_EQ(sc.cases[0].name, "first");
  ASSERT_EQ(sc.cases[0].steps.size(), 3u);  // the file's setup, the case's, its steps
  EXPECT_EQ(sc.cases[0].steps[0].kind, Step::Kind::Set);
  EXPECT_EQ(sc.cases[0].steps[1].kind, Step::Kind::Write);
  EXPECT_TRUE(sc.cases[0].steps[2].has_at);
  EXPECT_EQ(sc.cases[0].steps[2].at_us, 2500000u);
  EXPECT_EQ(sc.cases[0].steps[2].line, 9);
  EXPECT_EQ(sc.cases[1].name, "count[n=3,t=1s]");
  EXPECT_EQ(sc.cases[2].name, "count[n=5,t=2s]");
  EXPECT_EQ(sc.cases[2].steps[1].after_us, 2000000u);
  EXPECT_EQ(sc.cases[2].steps[1].cond.all.at(0).value, 5);
  EXPECT_EQ(sc.cases[2].steps[1].line, 16);  // a substituted step keeps its line
}

TEST(ScenarioFile, StepForms) {
  const Scenario sc = parse_scenario(
      "cell: a.yaml\n"
      "cases:\n"
      "  - name: c\n"
      "    steps:\n"
      "      - pulse: {X0: 100ms}\n"
      "      - ramp: {analog.level: {from: 0 V, to: 10 V, over: 2s}, R5: {from: 0, to: 100, over: 1s}}\n"
      "      - force: {Y0: off}\n"
      "      - release: all\n"
      "      - release: [Y0, M3]\n"
      "      - wait_until: Y1\n"
      "      - expect: R0 == 10\n"
      "        tolerance: 2\n"
      "        stays: 1s\n"
      "      - expect: Y2\n"
      "        between: [1s, 2s]\n"
      "      - expect_sequence: [Y0, {that: Y2, within: 1.5s}, {that: Y1, between: [1s, 2s]}]\n"
      "        timeout: 20s\n",
      "/d/s.yaml");
  const auto& s = sc.cases.at(0).steps;
  ASSERT_EQ(s.size(), 9u);
  EXPECT_EQ(s[0].assignments.at(0).duration_us, 100000u);
  EXPECT_EQ(s[1].assignments.size(), 2u);
  EXPECT_EQ(s[1].assignments[0].target.kind, Probe::Kind::Analog);
  EXPECT_EQ(s[1].assignments[0].value.unit, "V");
  EXPECT_EQ(s[1].assignments[0].value.number, 10);
  EXPECT_EQ(s[2].assignments.at(0).value.number, 0);
  EXPECT_TRUE(s[3].assignments.empty());  // all
  EXPECT_EQ(s[4].assignments.size(), 2u);
  EXPECT_EQ(s[5].timeout_us, kDefaultTimeoutUs);
  EXPECT_EQ(s[6].cond.all.at(0).tolerance, 2);
  EXPECT_EQ(s[6].stays_us, 1000000u);
  EXPECT_TRUE(s[7].has_window);
  EXPECT_EQ(s[7].window_min_us, 1000000u);
  EXPECT_EQ(s[7].window_max_us, 2000000u);
  ASSERT_EQ(s[8].sequence.size(), 3u);
  EXPECT_EQ(s[8].sequence[0].max_us, UINT64_MAX);
  EXPECT_EQ(s[8].sequence[1].max_us, 1500000u);
  EXPECT_EQ(s[8].sequence[2].min_us, 1000000u);
  EXPECT_EQ(s[8].timeout_us, 20000000u);
}

TEST(ScenarioFile, EveryErrorOfAFileInOneReading) {
  const auto e = errors_of(
      "cell: a.yaml\n"
      "colour: red\n"
      "cases:\n"
      "  - name: c\n"
      "    steps:\n"
      "      - expect: R0 =< 1\n"                       // 6
      "      - set: {X0: on}\n"
      "        write: {R0: 1}\n"                        // 8
      "      - after: 2 parsecs\n"                      // 9
      "      - at: 1s\n"
      "        after: 1s\n"                             // 11
      "      - expect: Y0\n"
      "        timeout: 1s\n"                           // 13
      "      - expect: Y0\n"
      "        stays: 1s\n"                             // 15
      "        within: 1s\n"
      "      - frobnicate: Y0\n"                        // 17
      "      - ramp: {R0: {from: 0, to: 5}}\n"           // 18
      "      - set: {analog.level: 5}\n"                // 19
      "      - set: {temperature.t: 5 V}\n"             // 20
      "      - force: {R0: 3}\n"                        // 21
      "      - set: {counter.belt: 0}\n"                // 22
      "      - expect: Y2\n"
      "        between: [2s, 1s]\n"                     // 24
      "      - expect_sequence: []\n"                   // 25
      "      - expect: R0 == ${n}\n"                    // 26
      "      - pulse: {X0: 0s}\n"                       // 27
      "      - {}\n"                                    // 28
      "  - name: c\n"                                   // 29
      "    steps: []\n"
      "  - name: rows\n"
      "    parameters:\n"
      "      - {n: 1}\n"
      "      - {m: 2}\n"                                // 34
      "    steps: []\n"
      "  - steps: []\n");                               // 36
  const std::vector<std::string> expected = {
      "/d/bad.yaml:2:1: error: key 'colour': unknown key (expected one of: cases, cell, explore, hardware, line, program, properties, setup)",
      "/d/bad.yaml:6:17: error: key 'cases[0].steps[0].expect': 'R0 =< 1': expected ==, !=, <, <=, > or >= after R0, got '=<'",
      "/d/bad.yaml:8:9: error: key 'cases[0].steps[1]': one action per step: 'set' and 'write'",
      "/d/bad.yaml:9:16: error: key 'cases[0].steps[2].after': bad duration '2 parsecs'",
      "/d/bad.yaml:11:16: error: key 'cases[0].steps[3].after': 'at' and 'after' exclude each other",
      "/d/bad.yaml:13:18: error: key 'cases[0].steps[4].timeout': 'timeout' goes with wait_until or expect_sequence",
      "/d/bad.yaml:15:16: error: key 'cases[0].steps[5].stays': 'stays' excludes 'within' and 'between'",
      "/d/bad.yaml:17:9: error: key 'cases[0].steps[6].frobnicate': unknown key (expected one of: after, at, ",
      "/d/bad.yaml:18:20: error: key 'cases[0].steps[7].ramp.R0': missing 'over'",
      "/d/bad.yaml:19:29: error: key 'cases[0].steps[8].set.analog.level': '5' has no unit: an analog input takes V or mA",
      "/d/bad.yaml:20:30: error: key 'cases[0].steps[9].set.temperature.t': a temperature channel takes C, mV, ohm or kohm, not V",
      "/d/bad.yaml:21:21: error: key 'cases[0].steps[10].force.R0': force takes on or off",
      "/d/bad.yaml:22:15: error: key 'cases[0].steps[11].set.counter.belt': counter.belt cannot be driven",
      "/d/bad.yaml:24:18: error: key 'cases[0].steps[12].between': the earliest time is after the latest",
      "/d/bad.yaml:25:26: error: key 'cases[0].steps[13].expect_sequence': expected a list of conditions",
      "/d/bad.yaml:26:17: error: key 'cases[0].steps[14].expect': ${n}: no parameter 'n' in this case",
      "/d/bad.yaml:27:21: error: key 'cases[0].steps[15].pulse': a pulse of 0 s is no pulse",
      "/d/bad.yaml:28:9: error: key 'cases[0].steps[16]': a step needs an action",
      "/d/bad.yaml:29:11: error: key 'cases[1].name': a second case named 'c'",
      "/d/bad.yaml:34:9: error: key 'cases[2].parameters[1]': every row needs the same names as the first",
      "/d/bad.yaml:36:5: error: key 'cases[3]': missing 'name'",
  };
  std::string all;
  for (const auto& s : e) all += s + "\n";
  ASSERT_EQ(e.size(), expected.size()) << all;
  for (size_t i = 0; i < expected.size(); ++i)
    EXPECT_EQ(e[i].rfind(expected[i], 0), 0u) << "expected: " << expected[i] << "\ngot: " << e[i];
}

TEST(ScenarioFile, TheFileItself) {
  EXPECT_EQ(errors_of("cases: []\n").at(0), "/d/bad.yaml:1:1: error: key 'cell': missing 'cell' (or 'line'): the cell YAML this scenario runs");
  EXPECT_NE(errors_of("cell: a.yaml\n").at(0).find("key 'cases': expected a list of test cases"), std::string::npos);
  EXPECT_NE(errors_of("- a\n").at(0).find("a scenario file is a mapping"), std::string::npos);
  EXPECT_NE(errors_of("cell: [a\n").at(0).find("/d/bad.yaml:2:"), std::string::npos);  // YAML syntax: its line
  try {
    load_scenario("/nonexistent/s.yaml");
    ADD_FAILURE();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/s.yaml: error: cannot open the scenario file /nonexistent/s.yaml"), std::string::npos) << e.what();
  }
}

// YAML is Unicode: a byte that is not UTF-8, or a raw control character, is refused where
// it is, like a syntax error, so no name that cannot be reported reaches a run.
TEST(ScenarioFile, TextThatIsNotUtf8IsRefusedAtItsLine) {
  EXPECT_EQ(errors_of("cell: a.yaml\ncases:\n  - name: caf\xE9 ok\n    steps: [{expect: Y0}]\n"),
            std::vector<std::string>{"/d/bad.yaml:3:14: error: not UTF-8: byte 0xE9 (a YAML file is Unicode text, "
                                     "read as UTF-8)"});
  // A sequence cut short, a stray continuation byte, an overlong form, a surrogate.
  for (const char* bad : {"\xC3", "\x80", "\xC0\xAF", "\xED\xA0\x80", "\xF4\x90\x80\x80"}) {
    const auto e = errors_of(std::string("cell: a.yaml\ncases:\n  - name: x") + bad + "\n    steps: [{expect: Y0}]\n");
    ASSERT_EQ(e.size(), 1u);
    EXPECT_EQ(e[0].rfind("/d/bad.yaml:3:12: error: not UTF-8: byte 0x", 0), 0u) << e[0];
  }
  EXPECT_EQ(errors_of("cell: a.yaml\ncases:\n  - name: a\x07" "b\n    steps: [{expect: Y0}]\n").at(0),
            "/d/bad.yaml:3:12: error: character U+0007 is not allowed in YAML text (a control character: in "
            "double quotes, write it as an escape such as \\x07)");
  // Characters beyond ASCII are welcome, and the column counts characters.
  EXPECT_TRUE(errors_of("cell: a.yaml\ncases:\n  - name: \xC3\xA9" "t\xC3\xA9 \xE2\x86\x92 \xF0\x9F\x99\x82\n"
                        "    steps: [{expect: Y0}]\n")
                  .empty());
  EXPECT_EQ(errors_of("cell: a.yaml\ncases:\n  - name: \xC3\xA9\xFF\n    steps: [{expect: Y0}]\n").at(0)
                .rfind("/d/bad.yaml:3:12: error: not UTF-8: byte 0xFF", 0),
            0u);
  // A file on disk, as plc_cell test reads it.
  const std::string path = ::testing::TempDir() + "/latin1.scenario.yaml";
  std::ofstream(path) << "cell: a.yaml\ncases:\n  - name: \xFC" "ber\n    steps: [{expect: Y0}]\n";
  try {
    load_scenario(path);
    ADD_FAILURE();
  } catch (const SourceError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":3:11: error: not UTF-8: byte 0xFC", 0), 0u) << e.what();
  }
}

// The cell and program a scenario names, checked at the lines that name them, with the
// path each led to (relative to the scenario's folder).
TEST(ScenarioFile, ACellOrProgramThatCannotBeOpenedIsAnErrorAtItsLine) {
  const std::string dir = (std::filesystem::path(::testing::TempDir()) / "scenario_missing").string();
  ASSERT_EQ(std::system(("mkdir -p " + dir).c_str()), 0);
  std::ofstream(dir + "/s.yaml") << "cell: cells/none.yaml\nprogram: /nonexistent/p.il\n"
                                    "cases:\n  - name: a\n    steps: [{expect: Y0}]\n";
  ErrorList errors;
  const Scenario sc = read_scenario(dir + "/s.yaml", errors);
  std::vector<std::string> e;
  try {
    errors.throw_if_any();
  } catch (const SourceError& x) {
    for (const auto& d : x.diagnostics()) e.push_back(d.to_string());
  }
  EXPECT_EQ(e, (std::vector<std::string>{
                   dir + "/s.yaml:1:7: error: key 'cell': cannot open the cell config: No such file or directory "
                         "(looked for " + dir + "/cells/none.yaml)",
                   dir + "/s.yaml:2:10: error: key 'program': cannot open the program file: No such file or "
                         "directory (looked for /nonexistent/p.il)"}));
  EXPECT_EQ(sc.cell, "");  // no cell is built from it: its own error would name neither line
}

TEST(ScenarioFile, NamesTheCellDoesNotHaveAreReportedForEveryCaseBeforeRunning) {
  plc_cell::testing::ScenarioCell cell("unknown_names");
  const Scenario sc = parse_scenario(
      "cell: cell.yaml\n"
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {strat: on}\n"
      "      - expect: counter.belt == 1 and axis.x.position == 0\n"
      "  - name: b\n"
      "    steps:\n"
      "      - expect: temperature.oven > 3 and analog.level > 1\n"
      "      - set: {analog.level: 1 V}\n"
      "      - expect: R1:f32 == 1\n",
      cell.dir() + "/s.yaml");
  CellTarget t(sc.cell, sc.program);
  std::vector<std::string> e;
  for (const auto& c : sc.cases)
    for (const auto& d : check_case(c, t)) e.push_back(d.to_string());
  const std::string f = cell.dir() + "/s.yaml:";
  const std::vector<std::string> expected = {
      f + "5: error: key 'set': 'strat' is neither a signal of cell t nor an address",
      f + "6: error: key 'expect': no counter named 'belt' in the cell's counters",
      f + "6: error: key 'expect': no axis named 'x' in the cell's axes",
      f + "9: error: key 'expect': no temperature channel named 'oven' in the cell's modules",
      f + "9: error: key 'expect': analog.level: an analog input is driven, not read",
      f + "10: error: key 'set': the cell has no analog modules (modules.analog)",
      f + "11: error: key 'expect': R1:f32: f32 needs a 32-bit address",
  };
  std::string all;
  for (const auto& s : e) all += s + "\n";
  ASSERT_EQ(e.size(), expected.size()) << all;
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(e[i].rfind(expected[i], 0), 0u) << e[i];
}
