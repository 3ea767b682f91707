// The native engine against the interpreter (docs/native-engine.md): machine-code runs,
// the fallback, the lockstep engine and every example cell, run side by side.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/native/lockstep.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/virtual_run.h"

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
  plc.locked([](ScanEngine& e, Memory&) {
    e.set_engine(EngineChoice::Lockstep);
    return 0;
  });
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
}

// Every example program, with its cell and simulated inputs, on both engines side by side
// for 60 virtual seconds: the two whole memories are compared after every scan.
TEST(NativeEngine, EveryExampleEqualsTheInterpreterFor60VirtualSeconds) {
  namespace fs = std::filesystem;
  std::vector<fs::path> programs;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(PLC_CELL_SOURCE_DIR) / "examples"))
    if (e.path().extension() == ".il") programs.push_back(e.path());
  std::sort(programs.begin(), programs.end());
  ASSERT_GE(programs.size(), 17u);  // every .il of examples/ at the time of writing
  for (const fs::path& il : programs) {
    // Its own cell, or else (a variant of a program, as broken_interlock.il) the cell of its
    // folder, named as the folder, running it in place of its program.
    fs::path yaml = il;
    yaml.replace_extension(".yaml");
    CellOverrides interp_engine;
    if (!fs::exists(yaml)) {
      yaml = il.parent_path() / (il.parent_path().filename().string() + ".yaml");
      interp_engine.program = il.string();
    }
    SCOPED_TRACE(il.string());
    ASSERT_TRUE(fs::exists(yaml)) << yaml;
    CellOverrides native_engine = interp_engine;
    interp_engine.run.push_back({"", "engine", {"interpreter"}, "test"});
    native_engine.run.push_back({"", "engine", {"native"}, "test"});
    Cell interp(yaml.string(), interp_engine, Cell::Purpose::Check);
    ASSERT_EQ(interp.plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); }), "interpreter");
    Cell native(yaml.string(), native_engine, Cell::Purpose::Check);
    const std::string status = native.plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
    ASSERT_EQ(status.rfind("native: ", 0), 0u) << status;
    ASSERT_TRUE(interp.plc().set_mode(RunMode::Run));
    ASSERT_TRUE(native.plc().set_mode(RunMode::Run));
    const uint64_t period = interp.scan_period_us();
    VirtualRun ri(interp.plc(), period), rn(native.plc(), period);
    uint64_t scans = 0;
    for (uint64_t t = 0; t < 60000000; t += period) {
      ri.run_for(period);
      rn.run_for(period);
      ++scans;
      const std::string d = native.plc().locked([&](ScanEngine&, Memory& nm) {
        return interp.plc().locked([&](ScanEngine& ie, Memory& im) {
          return first_difference(nm, im, ie.program(), "scan " + std::to_string(scans));
        });
      });
      ASSERT_EQ(d, "");
    }
    EXPECT_EQ(native.plc().mode(), interp.plc().mode());
  }
}
