// The demo program and every example program, laid out: comments above their networks,
// the cell's signal names beside the addresses, and a grid without overlaps.
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <utility>

#include "ladder_fixture.h"
#include "plc_cell/ladder/json.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace ladder {
namespace test {

namespace {

std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The program laid out in its cell (the YAML of the same name, or else the folder's
// instruction set without one).
Layout example(const std::filesystem::path& il) {
  std::filesystem::path yaml = il;
  yaml.replace_extension(".yaml");
  const std::string text = read(il.string());
  if (!std::filesystem::exists(yaml)) {
    const FunctionTable fns = SoftCell::functions();
    return layout(parse_program(text, il.string(), fns), text, {}, &fns);
  }
  SoftCell cell(yaml.string(), il.string());
  const FunctionTable& fns = cell.plc().functions();
  return layout(parse_program(text, il.string(), fns), text, cell.config().signals, &fns);
}

}  // namespace

TEST(LadderExamples, EveryExampleProgramIsLaidOut) {
  int programs = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator("examples")) {
    if (entry.path().extension() != ".il") continue;
    SCOPED_TRACE(entry.path().string());
    ++programs;
    const Layout l = example(entry.path());
    ASSERT_FALSE(l.networks.empty());
    for (const Network& n : l.networks) {
      EXPECT_FALSE(n.il.empty());
      if (!n.drawable) {
        EXPECT_FALSE(n.reason.empty());
        continue;
      }
      expect_a_sound_grid(n);
    }
    EXPECT_NO_THROW(to_json(l).dump());
  }
  EXPECT_GE(programs, 18);  // the folder held 18 when this was written
}

TEST(LadderExamples, TheConveyorDemoWithItsCommentsAndSignals) {
  const Layout l = example("examples/conveyor/conveyor.il");
  ASSERT_EQ(l.networks.size(), 9u);
  for (const Network& n : l.networks) EXPECT_TRUE(n.drawable) << n.index << ": " << n.reason;

  const Network& latch = l.networks[0];
  EXPECT_EQ(latch.comment, "Start/stop latch. M1924 is the first-scan pulse: the demo starts by itself.");
  EXPECT_TRUE(cell(latch, "X0", 0, 0));
  EXPECT_EQ(at(latch, "X0").name, "start_button");
  EXPECT_TRUE(cell(latch, "M1924", 1, 0));
  EXPECT_TRUE(cell(latch, "X1", 0, 1));
  EXPECT_EQ(at(latch, "X1").name, "stop_button");
  EXPECT_EQ(at(latch, "M0", "coil").name, "line_running");
  EXPECT_EQ(at(latch, "M0", "coil").col, 2);
  EXPECT_EQ(at(latch, "M0", "contact").row, 2);
  EXPECT_TRUE(vwire(latch, 0, 0, 2));
  EXPECT_TRUE(vwire(latch, 1, 0, 2));

  const Network& belt = l.networks[1];
  EXPECT_EQ(belt.comment,
            "The conveyor runs while the line runs and no part waits at the stopper,\n"
            "or while the stopper is down to let a part through.");
  EXPECT_EQ(at(belt, "X3").form, "nc");
  EXPECT_TRUE(cell(belt, "X3", 0, 1));
  EXPECT_TRUE(cell(belt, "Y1", 1, 1));
  EXPECT_EQ(at(belt, "Y0").name, "conveyor_run");

  const Network& pick = l.networks[2];
  EXPECT_TRUE(cell(pick, "Y2", 0, 3));
  EXPECT_TRUE(cell(pick, "T50", 1, 3));
  EXPECT_TRUE(vwire(pick, 3, 0, 1));

  EXPECT_EQ(l.networks[3].comment, "Picked: lower the stopper for 0.8 s so the carrier passes.");
  EXPECT_EQ(l.networks[4].comment, "");  // no comment right above ORG Y1
  EXPECT_EQ(at(l.networks[6], "T51").form, "up");
  EXPECT_EQ(at(l.networks[6], "C0").type, "counter");
  const Element& mov = l.networks[7].elements.at(1);
  EXPECT_EQ(mov.mnemonic, "MOV");
  EXPECT_EQ(mov.operands.at(0).address, "RC0");
  EXPECT_EQ(mov.operands.at(1).address, "R0");
  EXPECT_EQ(l.networks[8].elements.at(0).form, "END");
}

TEST(LadderExamples, APositioningFunTakesARowPerInput) {
  const Layout l = example("examples/motion/positioning.il");
  const Network& n = l.networks.at(2);  // ORG M1925 / LD M1000 / LD M1001 / HSPSO
  ASSERT_TRUE(n.drawable) << n.reason;
  const Element& f = n.elements.back();
  EXPECT_EQ(f.mnemonic, "HSPSO");
  EXPECT_EQ(f.fun, 140);
  ASSERT_EQ(f.inputs.size(), 3u);
  EXPECT_EQ(f.inputs[0].name, "EN");
  EXPECT_EQ(f.inputs[1].name, "PAU");
  EXPECT_EQ(f.inputs[2].name, "ABT");
  EXPECT_TRUE(cell(n, "M1925", 0, 0));
  EXPECT_TRUE(cell(n, "M1000", 1, 0));
  EXPECT_TRUE(cell(n, "M1001", 2, 0));
  EXPECT_EQ(f.inputs[2].row, 2);
  EXPECT_EQ(f.row, 0);
  EXPECT_EQ(f.col, 1);
}

TEST(LadderExamples, ACommentAtTheEndOfALineStaysWithItsElement) {
  const Layout l = lay("; the belt\n\nORG     M0          ; a network starts with ORG\nOUT Y0 // and ends here\nEND\n");
  const Network& n = l.networks.at(0);
  EXPECT_EQ(n.comment, "");  // a blank line separates it from the comment above
  EXPECT_EQ(at(n, "M0").comment, "a network starts with ORG");
  EXPECT_EQ(at(n, "Y0").comment, "and ends here");
  EXPECT_EQ(n.il.at(0).text, "ORG     M0          ; a network starts with ORG");
}

TEST(LadderExamples, CommentLinesInsideANetworkStayInItsIl) {
  const Layout l = lay(";; first\n;; two lines\nORG X0\n; between\nOUT Y0\nEND\n");
  const Network& n = l.networks.at(0);
  EXPECT_EQ(n.comment, "first\ntwo lines");
  ASSERT_EQ(n.il.size(), 3u);
  EXPECT_EQ(n.il[1].text, "; between");
  EXPECT_EQ(n.il[1].line, 4);
}

}  // namespace test
}  // namespace ladder
}  // namespace plc_cell
