// Interrupt arbitration (manual §9.1): higher priority pre-empts, lower or equal
// waits, nesting up to 5 levels. A test-only FUN 250 RAISE requests a source the
// way a hardware event does, from inside a routine.
#include "hsc_fixture.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace hsc {
namespace {

FunctionTable with_raise() {
  FunctionTable t = SoftCell::functions();
  FunctionSpec s;
  s.number = 250;
  s.mnemonic = "RAISE";
  s.operands = {{"N", OperandRole::Const}};
  s.allow_32 = false;
  s.handler = [](ExecContext& c, const BoundOperand* o) { timeline::Scheduler::find(c.engine)->raise(static_cast<int>(o[0].k)); };
  t.add(s);
  return t;
}

// Each routine: optionally raise another source, then take a ticket (R0 + 1) and
// store it in its own register, so the registers show the completion order.
std::string routine(const std::string& label, int raise, const std::string& reg) {
  std::string r = "LBL " + label + "\nORG M1925\n";
  if (raise >= 0) r += "FUN 250 RAISE N=" + std::to_string(raise) + "\n";
  return r + "FUN 15 INC D=R0\nFUN 8 MOV S=R0 D=" + reg + "\nRTI\n";
}

const char* kMain = "ORG M1924\nFUN 8 MOV S=255 D=R4162\nORG TU M1\nFUN 250 RAISE N=";

TEST(Interrupts, HigherPriorityPreemptsAtOnce) {
  // X0+I (priority 18) raises HSC0I (priority 10): HSC0I completes first.
  HscCell cell("counters:\n  interrupts: [X0+]\n",
               std::string(kMain) + std::to_string(kX0Up) + "\nEND\n" + routine("X0+I", kHsc0I, "R11") +
                   routine("HSC0I", -1, "R12"),
               with_raise());
  cell.put("M1", 1);
  cell.run(2000);
  EXPECT_EQ(cell.get("R12"), 1u);
  EXPECT_EQ(cell.get("R11"), 2u);
  ASSERT_EQ(cell.isrs.size(), 2u);
  EXPECT_EQ(cell.isrs[1].source, kHsc0I);
  EXPECT_EQ(cell.isrs[1].depth, 2);  // the second level: it started inside X0+I
}

TEST(Interrupts, LowerPriorityWaits) {
  HscCell cell("counters:\n  interrupts: [X0+]\n",
               std::string(kMain) + std::to_string(kHsc0I) + "\nEND\n" + routine("HSC0I", kX0Up, "R12") +
                   routine("X0+I", -1, "R11"),
               with_raise());
  cell.put("M1", 1);
  cell.run(2000);
  EXPECT_EQ(cell.get("R12"), 1u);
  EXPECT_EQ(cell.get("R11"), 2u);
  ASSERT_EQ(cell.isrs.size(), 2u);
  EXPECT_EQ(cell.isrs[1].depth, 1);  // first level again: after HSC0I returned
}

TEST(Interrupts, EqualPriorityWaits) {
  // HSC4 counts on X0, so HSC4I has X0+I's priority; X1+I (lower) and HSC4I (equal)
  // raised from X0+I... X0 is HSC4's input, so use X2+I raising HSC5I on X2.
  HscCell cell("counters:\n  hsc5: {mode: MD0, a: X3}\n  interrupts: [X2+]\n",
               std::string(kMain) + std::to_string(x_edge_source(2, false)) + "\nEND\n" +
                   routine("X2+I", kHsc4I + 1, "R11") + routine("HSC5I", -1, "R12"),
               with_raise());
  // HSC5 on X3 has priority 24, X2+I 22: HSC5I is lower. Make them equal:
  cell.with([&](HscUnit&) {
    auto& irq = cell.sched->interrupts();
    irq.set_priority(kHsc4I + 1, irq.priority(x_edge_source(2, false)));
    return 0;
  });
  cell.put("M1", 1);
  cell.run(2000);
  EXPECT_EQ(cell.get("R11"), 1u);  // X2+I finished first
  EXPECT_EQ(cell.get("R12"), 2u);
}

TEST(Interrupts, NestingStopsAtFiveLevels) {
  // 100MSI -> 50MSI -> 10MSI -> 5MSI -> 4MSI (depth 5) raises 3MSI: it waits for
  // 4MSI, then runs before 5MSI resumes (it is higher than 5MSI).
  std::string il = std::string(kMain) + std::to_string(kTimeBase0 + 7) + "\nEND\n";
  il += routine("100MSI", kTimeBase0 + 6, "R27");
  il += routine("50MSI", kTimeBase0 + 5, "R26");
  il += routine("10MSI", kTimeBase0 + 4, "R25");
  il += routine("5MSI", kTimeBase0 + 3, "R24");
  il += routine("4MSI", kTimeBase0 + 2, "R23");
  il += routine("3MSI", -1, "R22");
  HscCell cell("", il, with_raise());  // R4162 = FF: no periodic ticks, only the requests
  cell.put("M1", 1);
  cell.run(2000);
  EXPECT_EQ(cell.get("R23"), 1u);  // 4MSI
  EXPECT_EQ(cell.get("R22"), 2u);  // 3MSI, after 4MSI returned
  EXPECT_EQ(cell.get("R24"), 3u);
  EXPECT_EQ(cell.get("R25"), 4u);
  EXPECT_EQ(cell.get("R26"), 5u);
  EXPECT_EQ(cell.get("R27"), 6u);
  int deepest = 0;
  for (const auto& r : cell.isrs) deepest = std::max(deepest, r.depth);
  EXPECT_EQ(deepest, 5);  // 4MSI and then 3MSI at the 5th level, never a 6th
  EXPECT_EQ(cell.isrs.back().source, kTimeBase0 + 2);
}

TEST(Interrupts, SimultaneousEventsRunHighestFirstAndDisabledSourcesAreIgnored) {
  // HST0 and HST1 both expire at 1 ms; HST0I (priority 10) runs before HST1I (11).
  HscCell cell("counters:\n  hsc0: {type: timer}\n  hsc1: {type: timer}\n",
               "ORG M1924\nFUN 8D MOV S=10 D=DR4098\nFUN 93 CN=0 D=1\nFUN 8D MOV S=10 D=DR4102\n"
               "FUN 93 CN=1 D=1\nFUN 146 DIS LBL=HST1I\nORG M1925\nFUN 145 EN LBL=HST1I\nEND\n" +
                   routine("HST1I", -1, "R11") + routine("HST0I", -1, "R10"));
  cell.run(3000);
  EXPECT_EQ(cell.get("R10"), 1u);
  EXPECT_EQ(cell.get("R11"), 2u);
  ASSERT_EQ(cell.isrs.size(), 2u);
  EXPECT_EQ(cell.isrs[0].t_ns, 1000000u);
  EXPECT_EQ(cell.isrs[1].t_ns, 1000000u);
}

TEST(Interrupts, AProgramWithBothNamesOfASourceRunsTheNewOne) {
  // HSC0I is the new name of HST0I: a program that has both runs HSC0I when HST0 expires,
  // whichever comes first in the text.
  for (const bool old_first : {true, false}) {
    const std::string routines = old_first ? routine("HST0I", -1, "R11") + routine("HSC0I", -1, "R10")
                                           : routine("HSC0I", -1, "R10") + routine("HST0I", -1, "R11");
    HscCell cell("counters:\n  hsc0: {type: timer}\n",
                 "ORG M1924\nFUN 8D MOV S=10 D=DR4098\nFUN 93 CN=0 D=1\nEND\n" + routines);
    cell.run(3000);
    EXPECT_EQ(cell.get("R10"), 1u) << (old_first ? "HST0I first" : "HSC0I first");
    EXPECT_EQ(cell.get("R11"), 0u) << (old_first ? "HST0I first" : "HSC0I first");
  }
}

TEST(Interrupts, LabelsAndOldNames) {
  EXPECT_EQ(source_of_label("HSTAI"), kHstaI);
  EXPECT_EQ(source_of_label("ATMRI"), kHstaI);
  EXPECT_EQ(source_of_label("1MS"), kTimeBase0);
  EXPECT_EQ(source_of_label("100MSI"), kTimeBase0 + 7);
  EXPECT_EQ(source_of_label("HST2I"), kHsc0I + 2);
  EXPECT_EQ(source_of_label("INT15-"), x_edge_source(15, true));
  EXPECT_EQ(source_of_label("X3+I"), x_edge_source(3, false));
  EXPECT_EQ(source_of_label("HSC7I"), kHsc4I + 3);
  EXPECT_EQ(source_of_label("LOOP"), -1);
}

// A reserved label names an interrupt routine (after END, ended by RTI): the
// parser refuses it as a JMP/CALL target or as a label in the main program.
std::string parse_error(const std::string& il) {
  try {
    parse_program(il, "p.il", SoftCell::functions());
  } catch (const SourceError& e) {
    return e.diagnostics().at(0).to_string();
  }
  return "";
}

TEST(Interrupts, ReservedLabelsAreNoJumpTargets) {
  EXPECT_EQ(parse_error("ORG X0\nCALL HSC0I\nEND\nLBL HSC0I\nORG M1925\nOUT M0\nRTI\n"),
            "p.il:2:6: error: CALL HSC0I: HSC0I is an interrupt label; its routine runs on the interrupt, not by CALL");
  EXPECT_EQ(parse_error("ORG X0\nJMP x0+i\nEND\n"),
            "p.il:2:5: error: JMP X0+I: X0+I is an interrupt label; its routine runs on the interrupt, not by JMP");
  EXPECT_NE(parse_error("ORG X0\nCALL 1MS\nEND\n").find("1MS is an interrupt label"), std::string::npos);
  EXPECT_NE(parse_error("ORG X0\nJMP INT3-\nEND\n").find("INT3- is an interrupt label"), std::string::npos);
  EXPECT_EQ(parse_error("ORG X0\nOUT Y0\nLBL 1MSI\nORG X1\nOUT Y1\nEND\n"),
            "p.il:3:5: error: 1MSI is an interrupt label: its routine belongs after END (LBL 1MSI ... RTI)");
  // Ordinary labels and the routines themselves are fine.
  EXPECT_EQ(parse_error("ORG X0\nCALL SUB1\nEND\nLBL SUB1\nORG M1925\nOUT M0\nRTS\n"
                        "LBL HSTAI\nORG M1925\nOUT M1\nRTI\n"),
            "");
}

// An online change brings or takes away a time-base routine without STOP: the ticks
// (1 ms from RUN, manual §9.2) run it from the next scan, and stop with the program that
// has none.
TEST(Interrupts, ATimeBaseRoutineComesAndGoesWithAnOnlineChange) {
  const std::string without = "ORG M1925\nFUN 15 INC D=R1\nEND\n";
  const std::string with = without + "LBL 1MSI\nORG M1925\nFUN 15 INC D=R0\nRTI\n";
  HscCell cell("", without);
  cell.run(10000);  // scans at 0 .. 9 ms
  EXPECT_EQ(cell.get("R0"), 0u);
  cell.plc.load_program_text(with, "with.il");
  ASSERT_EQ(cell.plc.mode(), RunMode::Run);
  cell.run(10000);  // scans at 10 .. 19 ms: the ticks 10 .. 19 ms
  EXPECT_EQ(cell.get("R0"), 10u);
  EXPECT_EQ(cell.runs_of(kTimeBase0).size(), 10u);
  cell.plc.load_program_text(without, "without.il");
  cell.run(10000);
  EXPECT_EQ(cell.get("R0"), 10u);
  cell.plc.load_program_text(with, "with.il");  // and back
  cell.run(5000);
  EXPECT_EQ(cell.get("R0"), 15u);
  EXPECT_EQ(cell.get("R1"), 35u);  // the main program scanned throughout
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
