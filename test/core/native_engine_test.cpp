// The native engine against the interpreter (docs/native-engine.md): machine-code runs,
// the fallback, and the lockstep engine of a bare PLC (whole cells: lockstep_cells_test.cpp).
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/native/lockstep.h"
#include "plc_cell/core/plc.h"

using namespace plc_cell;

namespace {

// Two bare PLCs on one program, one per engine, with the same inputs every scan.
struct Pair {
  Plc interp, native;
  uint64_t now_us = 0;

  explicit Pair(const std::string& text) {
    for (Plc* p : {&interp, &native}) p->load_program_text(text, "pair.il");
    for (auto [p, e] : {std::pair{&interp, EngineChoice::Interpreter}, std::pair{&native, EngineChoice::Native}})
      p->locked([e = e](ScanEngine& se, Memory&) {
        se.set_engine(e);
        return 0;
      });
    for (Plc* p : {&interp, &native}) EXPECT_TRUE(p->set_mode(RunMode::Run));
    EXPECT_EQ(interp.locked([](ScanEngine& e, Memory&) { return e.engine_status(); }), "interpreter");
  }
  // Empty while both memories are equal after the scan.
  std::string scan(const std::function<bool(uint32_t)>& x) {
    for (Plc* p : {&interp, &native}) {
      for (uint32_t i = 0; i < 16; ++i) p->set_input(i, x(i));
      p->scan(now_us);
    }
    now_us += 1000;
    return native.locked([&](ScanEngine& ne, Memory& nm) {
      return interp.locked([&](ScanEngine& ie, Memory& im) {
        return first_difference(nm, im, ie.program(), "scan " + std::to_string(ne.stats().scans));
      });
    });
  }
  std::string status() {
    return native.locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
  }
};

void in_lockstep(Plc& plc) {
  plc.locked([](ScanEngine& e, Memory&) {
    e.set_engine(EngineChoice::Lockstep);
    return 0;
  });
}

// A FUN whose result depends on the engine that runs it (never so in the product): the
// interpreter writes 1, any other engine 2, into its operand.
FunctionTable skew_table() {
  FunctionTable t = FunctionTable::with_core_functions();
  FunctionSpec s;
  s.number = 961;
  s.mnemonic = "SKEW";
  s.operands = {{"D", OperandRole::Dest}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    c.put(o[0], c.engine && c.engine->engine() == EngineChoice::Interpreter ? 1 : 2);
  };
  t.add(s);
  return t;
}

}  // namespace

TEST(NativeEngine, CompilesTheNetworksBetweenFlowInstructionsAndSaysSo) {
  Pair p("ORG X0\nAND X1\nLD X2\nOR NOT X3\nANDLD\nOUT Y0\nOUT NOT Y1\nSET M5\n"
         "ORG X4\nTMR T0 10\nJMP L0\nORG T0\nOUT Y2\nAND X5\nOUT Y3\nLBL L0\nEND\n");
  // ORG X0 .. TMR T0 are one run, ORG T0 .. OUT Y3 the second; JMP, LBL and END stay handlers.
  EXPECT_EQ(p.status().rfind("native: 14 of 17 instructions in 2 machine-code runs", 0), 0u) << p.status();
  const native::NativeCode* nc = p.native.locked([](ScanEngine& e, Memory&) { return e.interpreter().native_code(); });
  ASSERT_NE(nc, nullptr);
  ASSERT_EQ(nc->runs().size(), 2u);
  EXPECT_EQ(nc->runs()[0].first, 0u);
  EXPECT_EQ(nc->runs()[0].length, 10u);
  EXPECT_EQ(nc->runs()[1].first, 11u);
  EXPECT_EQ(nc->runs()[1].length, 4u);
}

TEST(NativeEngine, IsTheDefault) {
  Plc plc;
  plc.load_program_text("ORG X0\nAND X1\nOUT Y0\nEND\n", "d.il");
  const auto [engine, status] = plc.locked([](ScanEngine& e, Memory&) { return std::pair{e.engine(), e.engine_status()}; });
  EXPECT_EQ(engine, EngineChoice::Native);
  EXPECT_EQ(status.rfind("native: 3 of 4 instructions in 1 machine-code runs", 0), 0u) << status;
}

TEST(NativeEngine, EqualsTheInterpreterOnEveryInputCombination) {
  // Blocks nested 9 deep: the first six levels live in registers, the rest in memory.
  std::string text = "ORG X0\n";
  for (int k = 1; k <= 9; ++k) text += (k % 2 ? "LD NOT X" : "LD X") + std::to_string(k) + "\n";
  for (int k = 9; k >= 1; --k) text += k % 3 ? "ORLD\n" : "ANDLD\n";
  text += "OUT Y0\nOUT NOT Y1\nAND NOT X10\nSET M7\nORG X11\nOR X12\nRST M7\nOUT M8\nEND\n";
  Pair p(text);
  EXPECT_NE(p.status().find("native: "), std::string::npos) << p.status();
  for (uint32_t v = 0; v < (1u << 13); ++v) {
    const std::string d = p.scan([v](uint32_t i) { return (v >> i) & 1u; });
    ASSERT_EQ(d, "") << "inputs " << v;
  }
}

TEST(NativeEngine, LeavesAForcedCoilAlone) {
  Pair p("ORG X0\nAND X1\nOUT Y0\nSET Y1\nEND\n");
  for (Plc* plc : {&p.interp, &p.native}) plc->force(parse_address("Y0"), ForceAction::Disable);
  ASSERT_EQ(p.scan([](uint32_t) { return true; }), "");
  EXPECT_EQ(p.native.read(parse_address("Y0"), 1).at(0), 0u);  // disabled: the program cannot set it
  EXPECT_EQ(p.native.read(parse_address("Y1"), 1).at(0), 1u);
}

TEST(NativeEngine, AnOnlineChangeSwapsTheCodeAndKeepsRunning) {
  Pair p("ORG X0\nAND X1\nOUT Y0\nEND\n");
  ASSERT_EQ(p.scan([](uint32_t) { return true; }), "");
  for (Plc* plc : {&p.interp, &p.native}) plc->load_program_text("ORG X0\nAND NOT X1\nOUT Y0\nOUT Y5\nEND\n", "b.il");
  EXPECT_EQ(p.native.mode(), RunMode::Run);
  ASSERT_EQ(p.scan([](uint32_t i) { return i == 0; }), "");
  EXPECT_EQ(p.native.read(parse_address("Y5"), 1).at(0), 1u);
  EXPECT_NE(p.status().find("native: 4 of 5"), std::string::npos) << p.status();
}

TEST(Lockstep, NamesTheAddressBothValuesTheInstructionAndTheScan) {
  Memory a, b;
  FunctionTable fns = FunctionTable::with_core_functions();
  const Program prog = parse_program("ORG X0\nOUT Y0\nORG X1\nMOV R5 D7\nEND\n", "ls.il", fns);
  EXPECT_EQ(first_difference(a, b, prog, "scan 3"), "");
  a.set_reg(Area::D, 7, 42);
  EXPECT_EQ(first_difference(a, b, prog, "scan 3"),
            "lockstep: D7 is 42 on the native engine and 0 on the interpreter after scan 3 (written by ls.il:4)");
  b.set_reg(Area::D, 7, 42);
  b.set_bit(Area::Y, 0, true);
  EXPECT_EQ(first_difference(a, b, prog, "scan 4"),
            "lockstep: Y0 is 0 on the native engine and 1 on the interpreter after scan 4 (written by ls.il:2)");
}

TEST(Lockstep, RunsBothEnginesAndStaysInRunWhileTheyAgree) {
  Plc plc;
  plc.load_program_text("ORG X0\nAND X1\nOUT Y0\nORG TU X0\nCTR C0 3\nORG C0\nOUT Y1\nEND\n", "l.il");
  in_lockstep(plc);
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  for (int s = 0; s < 20; ++s) {
    plc.set_input(0, s % 2);
    plc.set_input(1, s % 3 == 0);
    plc.scan(uint64_t(s) * 1000);
  }
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_EQ(plc.read(parse_address("Y1"), 1).at(0), 1u);
  const std::string status = plc.locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
  EXPECT_EQ(status.rfind("lockstep: native: ", 0), 0u) << status;
  EXPECT_NE(status.find("compared with the interpreter on a bare PLC after every scan and routine"), std::string::npos)
      << status;
}

// A bare twin has no subsystem: beside a PLC that has some, it would differ wherever they
// write. Such a PLC needs its whole cell as the twin (lockstep_cells_test.cpp).
TEST(Lockstep, ABareTwinIsRefusedBesideSubsystems) {
  struct Hook final : ScanHook {} hook;
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "h.il");
  const std::string why = plc.locked([&](ScanEngine& e, Memory&) {
    e.add_hook(&hook);
    std::string out;
    try {
      e.set_engine(EngineChoice::Lockstep);
    } catch (const Error& x) {
      out = x.what();
    }
    e.remove_hook(&hook);
    return out;
  });
  EXPECT_EQ(why, "lockstep: this PLC has 1 subsystem hook(s), so its twin must be the whole cell: build the cell "
                 "with plc.engine: lockstep or --engine lockstep");
  EXPECT_EQ(plc.locked([](ScanEngine& e, Memory&) { return e.engine(); }), EngineChoice::Native);
}

// A bare PLC's twin follows its online change, a STOP -> RUN between two scans, a client's
// write and the inputs: had it missed one, Y0 (the new program's), RC0 (counted again from
// the RUN) or R7 would differ, and the PLC would stop.
TEST(Lockstep, ABarePlcsTwinFollowsWhatThePlcIsGiven) {
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nORG TU X1\nCTR C0 100\nEND\n", "a.il");
  in_lockstep(plc);
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  uint64_t t = 0;
  for (int s = 0; s < 10; ++s, t += 1000) {
    plc.set_input(1, s % 2);
    plc.scan(t);
  }
  plc.load_program_text("ORG X0\nOUT NOT Y0\nORG TU X1\nCTR C0 100\nOUT Y1\nEND\n", "b.il");
  plc.set_mode(RunMode::Stop);
  plc.write(parse_address("R7"), {77});
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  for (int s = 0; s < 10; ++s, t += 1000) {
    plc.set_input(1, s % 2);
    plc.scan(t);
  }
  ASSERT_EQ(plc.mode(), RunMode::Run) << plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
  EXPECT_EQ(plc.read(parse_address("Y0"), 1).at(0), 1u);  // b.il's OUT NOT
  EXPECT_EQ(plc.read(parse_address("RC0"), 1).at(0), 5u);  // counted again from the STOP -> RUN
}

TEST(Lockstep, AnEngineSpecificResultStopsABarePlcWithItsAddress) {
  Plc plc(skew_table());
  plc.load_program_text("ORG X0\nOUT Y0\nORG X1\nFUN 961 SKEW D=D5\nEND\n", "skew.il");
  in_lockstep(plc);
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  for (uint64_t s = 0; s < 5; ++s) plc.scan(s * 1000);  // X1 off: SKEW does not run
  ASSERT_EQ(plc.mode(), RunMode::Run);
  plc.set_input(1, true);
  plc.scan(5000);  // the 6th scan
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  EXPECT_EQ(plc.locked([](ScanEngine& e, Memory&) { return e.fault(); }),
            "lockstep: D5 is 2 on the native engine and 1 on the interpreter after scan 6 at 0.005000 s "
            "(written by skew.il:4)");
}
