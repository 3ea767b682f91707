// Lockstep on whole cells (docs/native-engine.md, "Lockstep"): the cell on the native
// engine and its twin, the same cell on the interpreter with every extension (counters,
// axes, modules, RTC, simulation), given the same inputs and compared after every scan and
// every interrupt routine. Every example cell runs 60 virtual seconds so without a
// difference; a difference made on purpose (a FUN that answers by engine) stops the cell
// with its address, both values, the instruction and the instant.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "../reliability/temp_dir.h"
#include "plc_cell/config/extension_registry.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/virtual_run.h"

using namespace plc_cell;
namespace fs = std::filesystem;

namespace {

struct ExampleCell {
  std::string name;  // as the report names it
  fs::path yaml;
  std::string program;  // "" for the cell's own
};

// Every cell file of examples/ (examples/modbus and examples/tri hold bridge configurations, a
// *.line.yaml a line of cells), and
// every program with no cell of its own (a variant, such as broken_interlock.il), run by the
// cell of its folder, named as the folder, in place of its program.
std::vector<ExampleCell> example_cells() {
  std::vector<ExampleCell> out;
  const fs::path root = fs::path(PLC_CELL_SOURCE_DIR) / "examples";
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const fs::path& p = e.path();
    const std::string file = p.filename().string();
    const std::string folder = p.parent_path().filename().string();
    if (p.extension() == ".yaml" && folder != "modbus" && folder != "tri" && file.find(".scenario.") == std::string::npos &&
        file.find(".explore.") == std::string::npos && file.find(".fails.") == std::string::npos &&
        file.find(".line.") == std::string::npos)  // a line of cells (docs/lines.md): its cells are here each
      out.push_back({fs::relative(p, root).string(), p, ""});
    if (p.extension() == ".il" && !fs::exists(fs::path(p).replace_extension(".yaml"))) {
      const fs::path folder_cell = p.parent_path() / (p.parent_path().filename().string() + ".yaml");
      out.push_back({fs::relative(p, root).string(), folder_cell, p.string()});
    }
  }
  std::sort(out.begin(), out.end(), [](const ExampleCell& a, const ExampleCell& b) { return a.name < b.name; });
  return out;
}

CellOverrides in_lockstep(const std::string& program = "") {
  CellOverrides o;
  o.program = program;
  o.run.push_back({"", "engine", {"lockstep"}, "--engine"});
  return o;
}

std::string fault_of(Plc& plc) {
  return plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
}

// A made-up subsystem with a deliberately wrong native result: FUN 962 SKEW writes 1 into its
// operand on the interpreter and 2 on any other engine; FUN 963 FAILN throws on any engine
// but the interpreter.
class Skew : public CellExtension {
 public:
  std::string name() const override { return "skew"; }
  void install(const CellConfig&, FunctionTable& t) override {
    FunctionSpec s;
    s.number = 962;
    s.mnemonic = "SKEW";
    s.operands = {{"D", OperandRole::Dest}};
    s.handler = [](ExecContext& c, const BoundOperand* o) { c.put(o[0], on_interpreter(c) ? 1 : 2); };
    t.add(s);
    FunctionSpec f;
    f.number = 963;
    f.mnemonic = "FAILN";
    f.handler = [](ExecContext& c, const BoundOperand*) {
      if (!on_interpreter(c)) throw Error("not on the interpreter");
    };
    t.add(f);
  }
  void attach(const CellConfig&, Plc&, ErrorList&) override {}
  void detach(Plc&) override {}

 private:
  static bool on_interpreter(const ExecContext& c) { return c.engine && c.engine->engine() == EngineChoice::Interpreter; }
};

// The fault of cfg's cell in lockstep, run in RUN for duration_us: it must have stopped.
std::string fault_after(const std::string& cfg, uint64_t duration_us) {
  Cell cell(cfg, in_lockstep(), Cell::Purpose::Simulate);
  EXPECT_TRUE(cell.plc().set_mode(RunMode::Run));
  VirtualRun run(cell.plc(), cell.scan_period_us());
  run.run_for(duration_us);
  EXPECT_EQ(cell.plc().mode(), RunMode::Stop);
  return fault_of(cell.plc());
}

std::string write_cell(const TempDir& d, const std::string& yaml, const std::string& il) {
  std::ofstream(d.path() + "/skew.il") << il;
  std::ofstream(d.path() + "/cell.yaml") << "cell: {name: skew, program: skew.il}\n" << yaml;
  return d.path() + "/cell.yaml";
}

}  // namespace

TEST(Lockstep, EveryExampleCellRunsWholeFor60VirtualSeconds) {
  const std::vector<ExampleCell> cells = example_cells();
  ASSERT_GE(cells.size(), 18u);  // 17 cells and broken_interlock.il at the time of writing
  for (const ExampleCell& ex : cells) {
    SCOPED_TRACE(ex.name);
    Cell cell(ex.yaml.string(), in_lockstep(ex.program), Cell::Purpose::Simulate);
    ASSERT_NE(cell.twin(), nullptr);
    const std::string status = cell.plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
    EXPECT_EQ(status.rfind("lockstep: native: ", 0), 0u) << status;
    EXPECT_NE(status.find("compared with the interpreter on the whole cell"), std::string::npos) << status;
    ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
    VirtualRun run(cell.plc(), cell.scan_period_us());
    run.run_for(60000000);
    EXPECT_EQ(fault_of(cell.plc()), "");
    EXPECT_EQ(cell.plc().mode(), RunMode::Run);
    // The twin is the whole cell on the interpreter, and it made every scan.
    const auto [scans, twin_status] = cell.twin()->plc().locked(
        [](ScanEngine& e, Memory&) { return std::pair{e.stats().scans, e.engine_status()}; });
    EXPECT_EQ(scans, run.scans());
    EXPECT_EQ(twin_status, "interpreter");
    EXPECT_EQ(cell.twin()->extensions().size(), cell.soft().extensions().size());
  }
}

TEST(Lockstep, AWrongNativeResultInTheMainProgramStopsTheCell) {
  ExtensionRegistration skew("skew", [] { return std::make_unique<Skew>(); });
  TempDir d;
  // T0 (0.01 s base) reaches 0.5 s at the scan at 0.5 s, the 501st.
  const std::string cfg = write_cell(d, "", "ORG M1925\nTMR T0 50\nORG T0\nFUN 962 SKEW D=D5\nEND\n");
  EXPECT_EQ(fault_after(cfg, 1000000),
            "lockstep: D5 is 2 on the native engine and 1 on the interpreter after scan 501 at 0.500000 s "
            "(written by " + d.path() + "/skew.il:4)");
}

TEST(Lockstep, AWrongNativeResultInAnInterruptRoutineStopsTheCellThere) {
  ExtensionRegistration skew("skew", [] { return std::make_unique<Skew>(); });
  TempDir d;
  // A disk of 1500 rpm, one pulse a turn, on X0 (a pulse every 40 ms, the first at 40 ms):
  // HSC0 interrupts at its 10th pulse, at 0.4 s.
  const std::string cfg = write_cell(d,
                                     "counters:\n  hsc0: {mode: MD0, name: disk}\n  sources:\n"
                                     "    - {name: disk, a: X0, rpm: 1500, per_rev: 1}\n",
                                     "ORG M1924\nFUN 8D MOV S=0 D=DR4096\nFUN 93 HSCTW CN=0 D=0\n"
                                     "FUN 8D MOV S=10 D=DR4098\nFUN 93 HSCTW CN=0 D=1\nEND\n"
                                     "LBL HSC0I\nORG M1925\nFUN 962 SKEW D=D6\nRTI\n");
  EXPECT_EQ(fault_after(cfg, 1000000),
            "interrupt HSC0I: lockstep: D6 is 2 on the native engine and 1 on the interpreter after routine HSC0I "
            "at 0.400000 s (written by " + d.path() + "/skew.il:9)");
}

TEST(Lockstep, AFaultOnOneEngineOnlyStopsTheCell) {
  ExtensionRegistration skew("skew", [] { return std::make_unique<Skew>(); });
  TempDir d;
  const std::string cfg = write_cell(d, "", "ORG M1925\nTMR T0 2\nORG T0\nFUN 963 FAILN\nEND\n");
  EXPECT_EQ(fault_after(cfg, 100000),
            "lockstep: the native engine faulted (" + d.path() +
                "/skew.il:4: FUN 963 FAILN failed: not on the interpreter), the interpreter ran in scan 21 at "
                "0.020000 s");
}

// What the cell is given between two scans reaches the twin too: a client's write and
// forcing, a terminal a front end plays (the simulation overridden) and given back, RUN and
// STOP, an online change. Had the twin missed one, the cell would stop on a difference.
TEST(Lockstep, TheTwinIsGivenWhatTheCellIsGiven) {
  const fs::path conveyor = fs::path(PLC_CELL_SOURCE_DIR) / "examples/conveyor/conveyor.yaml";
  Cell cell(conveyor.string(), in_lockstep(), Cell::Purpose::Simulate);
  Plc& plc = cell.plc();
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  VirtualRun run(plc, cell.scan_period_us());
  const auto twin_reads = [&](const std::string& a) { return cell.twin()->plc().read(parse_address(a), 1).at(0); };
  run.run_for(2000000);
  plc.write(parse_address("R100"), {1234});
  plc.force(parse_address("Y1"), ForceAction::Disable);
  plc.force(parse_address("Y1"), ForceAction::Set);
  plc.locked([&](ScanEngine& e, Memory&) {
    cell.soft().simulation().override_input(0);  // a front end plays X0 from now on
    e.set_input(0, true);
    return 0;
  });
  run.run_for(3000000);
  EXPECT_EQ(twin_reads("R100"), 1234u);
  EXPECT_EQ(twin_reads("Y1"), 1u);
  EXPECT_EQ(twin_reads("X0"), 1u);
  plc.locked([&](ScanEngine&, Memory&) { return cell.soft().simulation().resume(0); });
  plc.force(parse_address("Y1"), ForceAction::Enable);
  ASSERT_TRUE(plc.set_mode(RunMode::Stop));
  run.run_for(100000);
  EXPECT_EQ(cell.twin()->plc().mode(), RunMode::Stop);
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  plc.load_program_file((fs::path(PLC_CELL_SOURCE_DIR) / "examples/conveyor/broken_interlock.il").string());
  run.run_for(10000000);
  EXPECT_EQ(fault_of(plc), "");
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_EQ(cell.twin()->plc().locked([](ScanEngine& e, Memory&) { return e.program().file; }),
            plc.locked([](ScanEngine& e, Memory&) { return e.program().file; }));
}

TEST(Lockstep, ACellWhoseProgramOwnsComPortsIsRefused) {
  TempDir d;
  const std::string cfg = write_cell(d, "ports:\n  1: {tcp: '127.0.0.1:1'}\n", "ORG M1925\nOUT Y0\nEND\n");
  try {
    Cell cell(cfg, in_lockstep(), Cell::Purpose::Simulate);
    FAIL() << "built";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "lockstep: the cell's FUN150/FUN151 own its COM ports (ports:), which its interpreter twin cannot "
              "share; run it on one engine");
  }
  Cell checked(cfg, in_lockstep(), Cell::Purpose::Check);  // no port is opened: nothing to share
  EXPECT_NE(checked.twin(), nullptr);
}
