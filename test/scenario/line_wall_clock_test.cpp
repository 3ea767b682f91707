// A line of cells over links as one wall-clock target (docs/lines.md, "On ROS"): each name
// CELL.NAME read, driven and put back on its own cell's PLC, the refusals of a name of no
// cell or of a cell out of reach at file:line, the rules per cell and the worst resolution.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "memory_plc.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/line_wall_clock.h"
#include "plc_cell/scenario/scenario_file.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::scenario_test::MemoryPlc;

namespace {

CellConfig line_cell(const std::string& name, const std::string& signals) {
  return parse_cell_config("cell: {name: " + name + ", program: t.il}\nsignals: {" + signals + "}\n",
                           "/d/" + name + ".yaml", Cell::sections());
}

Scenario line_scenario(const std::string& text) {
  return parse_scenario("line: l.line.yaml\nhardware: true\n" + text, "/d/s.yaml");
}

struct TwoCells {
  MemoryPlc a_plc, b_plc;
  CellConfig a = line_cell("a", "start: X0, motor: Y0");
  CellConfig b = line_cell("b", "part: X3, lamp: Y1");
  std::vector<LineCellLink> links{{"a", &a_plc, &a, ""}, {"b", &b_plc, &b, ""}};
};

std::string all_text(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) s += d.to_string() + "\n";
  return s;
}

}  // namespace

TEST(LineWallClockTarget, EachNameIsDrivenReadAndPutBackOnItsOwnCell) {
  TwoCells line;
  line.a_plc.plc.write(parse_address("R5"), {3});  // the same address in both cells
  const Scenario sc = line_scenario(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {a.start: on}\n"
      "      - write: {b.R5: 7}\n"
      "      - force: {b.lamp: on}\n"
      "      - after: 10ms\n"
      "        expect: a.X0 and b.R5 == 7 and a.R5 == 3 and b.lamp and not a.motor\n");
  const Case& c = sc.cases.at(0);
  LineWallClockTarget t(line.links, c, {});
  const CaseResult r = begin_and_run(c, t, [&t] { t.begin(); });
  EXPECT_TRUE(r.passed) << r.failure << "\n" << r.details;
  EXPECT_EQ(line.a_plc.log, (std::vector<std::string>{"force X0 1"}));
  EXPECT_EQ(line.b_plc.log, (std::vector<std::string>{"write R5 7", "force Y1 1"}));
  ASSERT_EQ(t.size(), 2u);
  EXPECT_EQ(t.label(parse_probe("a.start", Naming::Line)), "a.start (X0)");
  // Put back cell by cell: each PLC gets back only its own points.
  for (size_t i = 0; i < t.size(); ++i)
    EXPECT_TRUE(restore_points(t.plc(i), t.cell(i).found(), t.cell(i).touched(), {}).complete());
  EXPECT_FALSE(line.a_plc.disabled("X0"));
  EXPECT_FALSE(line.b_plc.disabled("Y1"));
  EXPECT_EQ(line.b_plc.value("R5"), 0u);
  EXPECT_EQ(line.a_plc.value("R5"), 3u);
  EXPECT_EQ(forces_and_writes_on_line(line.links, sc.cases), "forces a.start (X0), b.lamp (Y1); writes b.R5");
}

TEST(LineWallClockTarget, ANameOfNoCellOrOfACellOutOfReachIsRefusedAtItsLine) {
  TwoCells line;
  line.links[1].plc = nullptr;
  line.links[1].absent = "the cell 'b' of the line is not running on ROS";
  Scenario sc = line_scenario(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {c.start: on}\n"    // line 6
      "      - expect: b.lamp\n"        // line 7
      "      - expect: a.motor\n");     // line 8: fine
  const auto errors = all_text(refusals_on_line(line.links, "ros:/l", sc, {"the line", "", std::nullopt, 0},
                                                &sc.cases, nullptr));
  EXPECT_NE(errors.find("/d/s.yaml:6: error: key 'set': 'c.start': no cell 'c' in the line (a, b)"), std::string::npos)
      << errors;
  EXPECT_NE(errors.find("/d/s.yaml:7: error: key 'expect': 'b.lamp': the cell 'b' of the line is not running on ROS"),
            std::string::npos)
      << errors;
  EXPECT_EQ(errors.find("s.yaml:8:"), std::string::npos) << errors;
  EXPECT_TRUE(line.a_plc.log.empty());  // nothing written
}

TEST(LineWallClockTarget, TheRulesResolveEachNameInItsCell) {
  TwoCells line;
  Scenario sc = line_scenario(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {a.start: on, b.X0: on, b.lamp: on, b.R7: 1}\n"  // line 6: two inputs held, the rest written
      "      - expect: a.motor\n"
      "        within: 1ms\n");
  const auto errors = all_text(refusals_on_line(line.links, "ros:/l", sc, {"the line", "no force here", 5000, 0},
                                                &sc.cases, nullptr));
  EXPECT_NE(errors.find("key 'set': a.start (X0): the line cannot hold it: no force here"), std::string::npos) << errors;
  EXPECT_NE(errors.find("key 'set': b.X0: the line cannot hold it"), std::string::npos) << errors;
  EXPECT_EQ(errors.find("b.lamp"), std::string::npos) << errors;
  EXPECT_NE(errors.find("/d/s.yaml:7: error: key 'expect': within 1 ms is tighter than the resolution 5 ms"),
            std::string::npos)
      << errors;
  EXPECT_EQ(touched_in(line.links[0], sc.cases).size(), 1u);  // a.start, not b's R7
  EXPECT_EQ(touched_in(line.links[1], sc.cases).size(), 3u);  // b.X0, b.lamp and b.R7, not a.start
}

TEST(LineWallClockTarget, TheLineSeesTimeAsFinelyAsItsCoarsestCell) {
  Resolution fast, slow;
  fast.period_us = 2000, fast.scan_us = 1000, fast.polls = 20;
  slow.period_us = 2000, slow.scan_us = 2000, slow.age_us = 100000, slow.polls = 20;
  EXPECT_EQ(worst_resolution({fast, slow}).us(), slow.us());
  EXPECT_EQ(worst_resolution({slow, fast}).us(), slow.us());
}

namespace {

// A slow link: reads take read_ms, and saying which points are forced forced_ms (plc_node
// waits for its next ~forced): the cell whose points are read last starts its case late.
class SlowLink : public MemoryPlc {
 public:
  SlowLink(int read_ms, int forced_ms) : read_ms_(read_ms), forced_ms_(forced_ms) {}
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(read_ms_));
    return MemoryPlc::read(addrs);
  }
  std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) override {
    std::this_thread::sleep_for(std::chrono::milliseconds(forced_ms_));
    return MemoryPlc::forced(bits);
  }

 private:
  int read_ms_, forced_ms_;
};

}  // namespace

TEST(LineWallClockTarget, EveryCellCountsTheCaseFromOneTimeZero) {
  SlowLink a_plc(10, 0), b_plc(20, 300);
  const CellConfig a = line_cell("a", "start: X0"), b = line_cell("b", "part: X3");
  const std::vector<LineCellLink> links{{"a", &a_plc, &a, ""}, {"b", &b_plc, &b, ""}};
  const Scenario sc = line_scenario(
      "cases:\n"
      "  - name: a\n"
      "    steps:\n"
      "      - set: {b.part: on}\n"
      "      - expect: a.start == 0 and b.part\n");
  LineWallClockTarget t(links, sc.cases.at(0), {});  // no wait: each scan polls at once
  t.begin();
  t.scan(2000);
  // a's points were read before b's 300 ms answer: a case clock of its own would put this
  // scan 300 ms late.
  EXPECT_LT(t.scanned_at(2000), 150000u);
  // A reading of the line is as spread as its widest cell's, and more: its polls in turn.
  EXPECT_GE(t.spread_us(), t.cell(0).spread_us() + t.cell(1).slowest_poll_us());
  EXPECT_GE(t.spread_us(), t.cell(1).spread_us() + t.cell(0).slowest_poll_us());
}
