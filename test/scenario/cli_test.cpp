// plc_cell test as a user runs it: the examples, the one that fails on purpose, JUnit, -k,
// the same output every run, and bad files.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include "../core/run_tool.h"

using plc_cell::testing::run_tool;
using plc_cell::testing::ToolResult;

namespace {

const std::string kSrc = PLC_CELL_SOURCE_DIR;
const std::string kExamples = kSrc + "/examples/conveyor/conveyor.scenario.yaml " + kSrc +
                              "/examples/hsc/count_up_stop.scenario.yaml " + kSrc +
                              "/examples/motion/positioning.scenario.yaml " + kSrc + "/examples/oven/oven.scenario.yaml";

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

size_t count(const std::string& s, const std::string& part) {
  size_t n = 0;
  for (size_t p = s.find(part); p != std::string::npos; p = s.find(part, p + 1)) ++n;
  return n;
}

}  // namespace

TEST(ScenarioCli, TheExamplesPassWithOneLinePerCaseAndJUnit) {
  const std::string xml = ::testing::TempDir() + "/scenario_examples.xml";
  const ToolResult r = run_tool("test " + kExamples + " --junit " + xml);
  EXPECT_EQ(r.status, 0) << r.out;
  // conveyor 7 (a parameterised case of 3 rows), count-up stop 2, positioning 2, oven 3.
  EXPECT_EQ(count(r.out, "PASS  "), 14u) << r.out;
  EXPECT_TRUE(has(r.out, "\n== 14 passed, 0 failed (")) << r.out;
  EXPECT_TRUE(has(r.out, "PASS  " + kSrc + "/examples/conveyor/conveyor.scenario.yaml: counts every part[parts=3,at=14s]  (14.000 s)\n"))
      << r.out;
  const std::string x = slurp(xml);
  EXPECT_TRUE(has(x, "<testsuites name=\"plc_cell test\" tests=\"14\" failures=\"0\"")) << x;
  EXPECT_EQ(count(x, "<testsuite "), 4u);
  EXPECT_EQ(count(x, "<testcase "), 14u);
  EXPECT_EQ(count(x, "<failure"), 0u);
}

TEST(ScenarioCli, TheFailingExampleNamesItsExpectation) {
  const std::string xml = ::testing::TempDir() + "/scenario_fails.xml";
  const ToolResult r = run_tool("test " + kSrc + "/examples/conveyor/too_strict.fails.yaml --junit " + xml);
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, "PASS  " + kSrc + "/examples/conveyor/too_strict.fails.yaml: the belt runs")) << r.out;
  EXPECT_TRUE(has(r.out, "FAIL  " + kSrc + "/examples/conveyor/too_strict.fails.yaml: the stopper lowers 1 s after the part arrives  (2.000 s)\n"))
      << r.out;
  // The expectation that failed (the sequence's second entry, line 17), the value, the
  // time, and the changes: the part arrived at 1.000 s, the stopper had not lowered at 2 s.
  EXPECT_TRUE(has(r.out, "too_strict.fails.yaml:15: expect_sequence: entry 2 (line 17) 'stopper_lower' did not happen "
                         "within 1.000 s of entry 1's match at 1.000 s: stopper_lower (Y1) is OFF\n"))
      << r.out;
  EXPECT_TRUE(has(r.out, "      at 2.000 s\n")) << r.out;
  EXPECT_TRUE(has(r.out, "        pick_request (Y2):  initially OFF  1.000 s ON\n")) << r.out;
  EXPECT_TRUE(has(r.out, "== 1 passed, 1 failed")) << r.out;
  const std::string x = slurp(xml);
  EXPECT_TRUE(has(x, "tests=\"2\" failures=\"1\"")) << x;
  EXPECT_TRUE(has(x, "<failure message=\"" + kSrc + "/examples/conveyor/too_strict.fails.yaml:15: expect_sequence: entry 2 (line 17)"))
      << x;
}

TEST(ScenarioCli, KSelectsCasesByName) {
  const ToolResult r = run_tool("test " + kSrc + "/examples/conveyor/conveyor.scenario.yaml -k 'counts every'");
  EXPECT_EQ(r.status, 0) << r.out;
  EXPECT_EQ(count(r.out, "PASS  "), 3u) << r.out;
  const ToolResult one = run_tool("test " + kSrc + "/examples/conveyor/conveyor.scenario.yaml -k 'parts=2'");
  EXPECT_EQ(count(one.out, "PASS  "), 1u) << one.out;
  const ToolResult none = run_tool("test " + kSrc + "/examples/conveyor/conveyor.scenario.yaml -k nothing");
  EXPECT_EQ(none.status, 1);
  EXPECT_TRUE(has(none.out, "plc_cell test: no case matches -k 'nothing'")) << none.out;
}

TEST(ScenarioCli, TheSameRunGivesTheSameOutputAndTheSameJUnit) {
  const std::string a = ::testing::TempDir() + "/scenario_a.xml", b = ::testing::TempDir() + "/scenario_b.xml";
  const std::string files = kExamples + " " + kSrc + "/examples/conveyor/too_strict.fails.yaml";
  const ToolResult r1 = run_tool("test " + files + " --junit " + a);
  const ToolResult r2 = run_tool("test " + files + " --junit " + b);
  EXPECT_EQ(r1.status, 1);
  EXPECT_EQ(r1.out, r2.out);
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_FALSE(slurp(a).empty());
}

TEST(ScenarioCli, EveryErrorOfEveryFileBeforeAnyCaseRuns) {
  const std::string dir = ::testing::TempDir();
  std::ofstream(dir + "/bad1.scenario.yaml") << "cell: " << kSrc << "/examples/conveyor/conveyor.yaml\n"
                                                "cases:\n"
                                                "  - name: a\n"
                                                "    steps:\n"
                                                "      - expect: conveyor_runs\n"
                                                "      - after: soon\n";
  std::ofstream(dir + "/bad2.scenario.yaml") << "cell: " << kSrc << "/examples/conveyor/conveyor.yaml\n"
                                                "cases:\n"
                                                "  - name: b\n"
                                                "    steps:\n"
                                                "      - wait_until: axis.x.state == idle\n";
  const ToolResult r = run_tool("test " + dir + "/bad1.scenario.yaml " + dir + "/bad2.scenario.yaml");
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_TRUE(has(r.out, dir + "/bad1.scenario.yaml:6:16: error: key 'cases[0].steps[1].after': bad duration 'soon'"))
      << r.out;
  EXPECT_TRUE(has(r.out, dir + "/bad2.scenario.yaml:5: error: key 'wait_until': no axis named 'x' in the cell's axes"))
      << r.out;
  // The unknown signal of a step that reads well, in the same run as the syntax error.
  EXPECT_TRUE(has(r.out, dir + "/bad1.scenario.yaml:5: error: key 'expect': 'conveyor_runs' is neither a signal of cell "
                           "conveyor_demo nor an address"))
      << r.out;
  EXPECT_TRUE(has(r.out, "plc_cell test: 3 error(s) in the scenario files; no case ran")) << r.out;
  EXPECT_FALSE(has(r.out, "PASS")) << r.out;
}

TEST(ScenarioCli, UsageErrors) {
  EXPECT_EQ(run_tool("test").status, 2);
  EXPECT_EQ(run_tool("test x.yaml --junk").status, 2);
  const ToolResult missing = run_tool("test /nonexistent.scenario.yaml");
  EXPECT_EQ(missing.status, 1);
  EXPECT_TRUE(has(missing.out, "/nonexistent.scenario.yaml: error: cannot open the scenario file")) << missing.out;
}

// The run as CI does it: JUnit, and rung coverage summed over every case of every file.
TEST(ScenarioCli, CoverageOfTheWholeRun) {
  const std::string dir = ::testing::TempDir() + "/scenario_cov";
  const ToolResult r = run_tool("test " + kExamples + " --junit " + dir + ".xml --coverage --coverage-json " + dir +
                                ".json --coverage-html " + dir);
  EXPECT_EQ(r.status, 0) << r.out;
  // The cells' engine is native by default, but a recording runs the interpreter: said once.
  EXPECT_TRUE(has(r.out, " of virtual time)\ncoverage: every case ran on the interpreter's recording loop\ncoverage of "))
      << r.out;
  // The conveyor's seven cases together exercise all of it (its ORG M1925 network reads a
  // relay that is ON by definition: not measured).
  EXPECT_TRUE(has(r.out, "coverage of " + kSrc + "/examples/conveyor/conveyor.il (7 runs)\n"
                         "  networks evaluated 8/8, energised 8/8\n"
                         "  contacts changed 15/15, coils switched 8/8, FUNs enabled 1/1\n"
                         "  contacts with MC/DC (unique cause) 14/15\n"
                         "  every network, contact, coil and FUN exercised\n"))
      << r.out;
  // The count-up stop never runs the motor again after the stop: RST Y0's rung is always ON.
  // Y0 is the cell's signal motor: the finding names both.
  EXPECT_TRUE(has(r.out, kSrc + "/examples/hsc/count_up_stop.il:13 coil RST motor (Y0) never switched (rung always ON)"))
      << r.out;
  const std::string html = slurp(dir + "/index.html");
  for (const char* p : {"conveyor/conveyor.il", "hsc/count_up_stop.il", "motion/positioning.il", "oven/oven.il"}) {
    EXPECT_TRUE(has(html, p)) << p;
    EXPECT_TRUE(has(slurp(dir + ".json"), p)) << p;
  }
  // Coverage without a flag is not recorded: the same run prints no coverage.
  const ToolResult plain = run_tool("test " + kSrc + "/examples/conveyor/conveyor.scenario.yaml");
  EXPECT_FALSE(has(plain.out, "coverage of")) << plain.out;
  EXPECT_FALSE(has(plain.out, "recording loop")) << plain.out;
}

// End to end: a folder whose name is not UTF-8 and a case name with control characters
// (written as YAML escapes) give JUnit that an XML parser reads, with the bytes shown.
TEST(ScenarioCli, JUnitOfHostileNamesParses) {
  const std::string dir = ::testing::TempDir() + "/hostile_\xFF\x01<&\"dir";
  ::mkdir(dir.c_str(), 0755);
  std::ofstream(dir + "/cell.il") << "ORG X0\nOUT Y0\nEND\n";
  std::ofstream(dir + "/cell.yaml") << "cell: {name: t, program: cell.il}\nplc: {scan_period: 0.001}\n";
  std::ofstream(dir + "/s.yaml") << "cell: cell.yaml\ncases:\n"
                                    "  - name: \"tab\\there bell\\a nul\\0 esc\\e <&> \\u00e9\"\n"
                                    "    steps:\n      - expect: Y0\n";
  std::ofstream(::testing::TempDir() + "/hostile_check.py")
      << "import sys, xml.etree.ElementTree as E\n"
         "root = E.parse(sys.argv[1]).getroot()\n"
         "case = root.find('testsuite/testcase')\n"
         "assert case.get('name') == 'tab\\there bell\\\\u0007 nul\\\\u0000 esc\\\\u001B <&> \\u00e9', case.get('name')\n"
         "assert case.get('file').endswith('hostile_\\\\xFF\\\\u0001<&\"dir/s.yaml'), case.get('file')\n"
         "msg = case.find('failure').get('message')\n"
         "assert msg.endswith('hostile_\\\\xFF\\\\u0001<&\"dir/s.yaml:5: expect Y0: Y0 is OFF'), msg\n"
         "print('parsed')\n";
  setenv("PLC_CELL_HOSTILE", dir.c_str(), 1);
  const ToolResult r = run_tool("test \"$PLC_CELL_HOSTILE/s.yaml\" --junit \"$PLC_CELL_HOSTILE/out.xml\"");
  EXPECT_EQ(r.status, 1) << r.out;
  const ToolResult parsed = plc_cell::testing::run_shell("/usr/bin/python3 " + ::testing::TempDir() +
                                                         "/hostile_check.py \"$PLC_CELL_HOSTILE/out.xml\"");
  EXPECT_EQ(parsed.status, 0) << parsed.out;
  EXPECT_TRUE(has(parsed.out, "parsed")) << parsed.out;
}
