// A program change in RUN (docs/online-change.md): swapped at a scan boundary, the new program
// keeps the memory, the timers (value, running state and the part of a tick already counted),
// the counters, the edge memories of the instructions it still has, the forces and the
// retentive image, and sees no first-scan pulse; on the interpreter, the native engine and in
// lockstep, where the twin makes the same change at the same boundary.
#include <gtest/gtest.h>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/online_change.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {
namespace {

// M1924 (first scan) sets M10; X0 times T50 (0.1 s base, 10 s); a rising X1 counts C0; R5
// shows which program runs.
std::string program(int preset, int marker, bool with_timer = true) {
  return std::string("ORG M1924\nSET M10\n") + (with_timer ? "ORG X0\nTMR T50 100\n" : "") +
         "ORG TU X1\nCTR C0 " + std::to_string(preset) + "\nORG M1925\nFUN 8 S=" + std::to_string(marker) +
         " D=R5\nORG X2\nOUT Y2\nEND\n";
}

uint32_t at(Plc& plc, const char* a) { return plc.read(parse_address(a), 1).at(0); }

class OnlineChange : public ::testing::TestWithParam<EngineChoice> {
 protected:
  void SetUp() override {
    plc.load_program_text(program(9999, 1), "oc.il");
    plc.locked([&](ScanEngine& e, Memory&) {
      e.set_engine(GetParam());
      return 0;
    });
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
    scan();
    ASSERT_EQ(at(plc, "M10"), 1u) << "the first scan's pulse";
    plc.write(parse_address("M10"), {0});
    plc.set_input(0, true);
    plc.set_input(1, true);  // counted once, then held
    for (int i = 0; i < 3050; ++i) scan();
    plc.force(parse_address("Y3"), ForceAction::Disable);
    plc.force(parse_address("Y3"), ForceAction::Set);
    plc.write(parse_address("R100"), {1234});
    ASSERT_EQ(at(plc, "RT50"), 30u);
    ASSERT_EQ(at(plc, "RC0"), 1u);
  }
  void scan() {
    now += 1000;
    plc.scan(now);
  }
  // The change at this scan boundary, as the change service makes it.
  std::vector<std::string> change(const std::string& text) {
    const Program next = parse_program(text, "oc.il", plc.functions());
    return plc.locked([&](ScanEngine& e, Memory&) {
      auto why = online_change_refusals(e, next);
      if (why.empty()) e.load_online(next);
      return why;
    });
  }
  std::string fault() {
    return plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
  }

  Plc plc;
  uint64_t now = 0;
};

TEST_P(OnlineChange, KeepsEveryKindOfState) {
  ASSERT_TRUE(change(program(5000, 2)).empty());
  scan();
  EXPECT_EQ(at(plc, "R5"), 2u) << "the new program runs from the next scan";
  EXPECT_EQ(at(plc, "M10"), 0u) << "no first-scan pulse for a change in RUN";
  EXPECT_EQ(at(plc, "RC0"), 1u) << "the TU contact on X1 kept its edge memory: X1 held on is no new edge";
  EXPECT_EQ(at(plc, "RT50"), 30u) << "the timer kept its value";
  EXPECT_EQ(at(plc, "Y3"), 1u) << "the force holds";
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.disabled(Area::Y, 3); }));
  EXPECT_EQ(at(plc, "R100"), 1234u);
  // 10 s after X0 came on (3.05 s before the change), not 10 s after the change.
  for (int i = 0; i < 6940; ++i) scan();
  EXPECT_EQ(at(plc, "T50"), 0u) << "at 9.99 s";
  for (int i = 0; i < 20; ++i) scan();
  EXPECT_EQ(at(plc, "T50"), 1u) << "at 10.01 s";
  plc.set_input(1, false);
  scan();
  plc.set_input(1, true);
  scan();
  EXPECT_EQ(at(plc, "RC0"), 2u) << "a new rising edge still counts";
  EXPECT_EQ(fault(), "");
  EXPECT_EQ(plc.mode(), RunMode::Run);
}

// What the change keeps is what a download (load) loses: the same steps through load() re-fire
// the first-scan pulse and the held edge, and restart the timer.
TEST_P(OnlineChange, ADownloadInsteadLosesIt) {
  const Program next = parse_program(program(5000, 2), "oc.il", plc.functions());
  plc.load_program(next);
  scan();
  EXPECT_EQ(at(plc, "M10"), 1u);
  EXPECT_EQ(at(plc, "RC0"), 2u);
  EXPECT_EQ(at(plc, "RT50"), 0u);
}

TEST_P(OnlineChange, RefusesToDropATimerThatIsTiming) {
  const auto why = change(program(5000, 2, false));
  ASSERT_EQ(why.size(), 1u);
  EXPECT_NE(why[0].find("T50 is timing (TMR at oc.il:4)"), std::string::npos) << why[0];
  scan();
  EXPECT_EQ(at(plc, "R5"), 1u) << "the running program is untouched";
  EXPECT_EQ(at(plc, "RT50"), 30u);
  plc.set_input(0, false);  // its rung off: the timer stops, and may go
  scan();
  EXPECT_TRUE(change(program(5000, 2, false)).empty());
  scan();
  EXPECT_EQ(at(plc, "R5"), 2u);
  EXPECT_EQ(fault(), "");
}

INSTANTIATE_TEST_SUITE_P(Engines, OnlineChange,
                         ::testing::Values(EngineChoice::Interpreter, EngineChoice::Native, EngineChoice::Lockstep),
                         [](const auto& info) { return std::string(engine_choice_name(info.param)); });

TEST(CarriedEdges, AnEdgeInstructionKeepsItsMemoryWhereverItMoves) {
  const FunctionTable fns = FunctionTable::with_core_functions();
  const Program a = parse_program("ORG TU X1\nOUT Y1\nORG TD X2\nOUT Y2\nEND\n", "a.il", fns);
  // X2's falling edge first now, X1's second, and a new rising contact on X3.
  const Program b = parse_program("ORG TD X2\nOUT Y2\nORG TU X3\nOUT Y3\nORG TU X1\nOUT Y1\nEND\n", "b.il", fns);
  const auto from = carried_edges(a, b);
  ASSERT_EQ(from.size(), 3u);
  EXPECT_EQ(from[b.edge_slot_of[0]], a.edge_slot_of[2]);
  EXPECT_EQ(from[b.edge_slot_of[2]], ~0u) << "a new edge contact starts from 0";
  EXPECT_EQ(from[b.edge_slot_of[4]], a.edge_slot_of[0]);
}

}  // namespace
}  // namespace plc_cell
