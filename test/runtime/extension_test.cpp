// The extension model: every subsystem of a cell goes through install, attach, status
// and detach in one place (SoftCell), and a subsystem added by a caller is taken through
// the same steps as the built-in ones, its FUN reaching its per-PLC object in O(1).
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "../reliability/temp_dir.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/runtime/cell.h"

using namespace plc_cell;

namespace {

// A made-up subsystem: FUN 900 TICK counts its enabled scans into the object attached to
// the PLC that runs it, and a `ticker: {start: N}` section presets the count.
struct Ticker : public CellExtension {
  std::vector<std::string>* log;
  int ticks = 0;
  explicit Ticker(std::vector<std::string>* l) : log(l) {}
  std::string name() const override { return "ticker"; }
  std::vector<std::string> sections() const override { return {"ticker"}; }
  void install(const CellConfig&, FunctionTable& t) override {
    log->push_back("install");
    FunctionSpec s;
    s.number = 900;
    s.mnemonic = "TICK";
    s.handler = [](ExecContext& c, const BoundOperand*) {
      if (c.engine) ++c.engine->extensions().get<Ticker>()->ticks;
    };
    t.add(s);
  }
  void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) override {
    log->push_back("attach");
    const YAML::Node n = cfg.document["ticker"];
    errors.collect([&] {
      if (n && n["start"]) ticks = n["start"].as<int>();
    }, cfg.file, n);
    plc.locked([&](ScanEngine& e, Memory&) {
      e.extensions().attach(this);
      return 0;
    });
  }
  std::vector<ExtensionStatus> status(Plc&) const override {
    ExtensionStatus s;
    s.name = "ticker";
    s.message = std::to_string(ticks) + " ticks";
    return {s};
  }
  void detach(Plc& plc) override {
    log->push_back("detach");
    plc.locked([&](ScanEngine& e, Memory&) {
      e.extensions().detach(this);
      return 0;
    });
  }
};

std::string write_cell(TempDir& d, const std::string& yaml, const std::string& il) {
  std::ofstream(d.path() + "/p.il") << il;
  std::ofstream(d.path() + "/cell.yaml") << "cell: {program: p.il}\n" << yaml;
  return d.path() + "/cell.yaml";
}

}  // namespace

TEST(Extensions, ACallersExtensionGoesThroughEveryStep) {
  TempDir d;
  const std::string cfg = write_cell(d, "ticker: {start: 5}\n", "ORG M1925\nFUN 900\nEND\n");  // M1925: always on
  std::vector<std::string> log;
  {
    CellExtensions more;
    more.push_back(std::make_unique<Ticker>(&log));
    SoftCell cell(cfg, "", std::move(more));
    EXPECT_EQ(log, (std::vector<std::string>{"install", "attach"}));  // FUN 900 parsed: installed first
    const CellExtension& x = *cell.extensions().back();
    ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
    for (uint64_t t = 0; t < 3; ++t) cell.plc().scan(t * 1000);
    EXPECT_EQ(x.status(cell.plc()).at(0).message, "8 ticks");  // 5 from the YAML, one per scan
  }
  EXPECT_EQ(log, (std::vector<std::string>{"install", "attach", "detach"}));
}

TEST(Extensions, TheBuiltInSubsystemsAndTheCellsComeInOrder) {
  TempDir d;
  Cell cell(write_cell(d, "", "ORG M1925\nOUT Y0\nEND\n"), {}, Cell::Purpose::Check);
  std::vector<std::string> names;
  for (const auto& x : cell.soft().extensions()) names.push_back(x->name());
  EXPECT_EQ(names, (std::vector<std::string>{"modules", "counters", "axes", "gate", "protocol functions", "servers"}));
}

// Every section an extension claims is a section of the cell file, and every section of
// the file is the core's or an extension's.
TEST(Extensions, TheirSectionsAreTheCellFilesSections) {
  TempDir d;
  Cell cell(write_cell(d, "", "ORG M1925\nOUT Y0\nEND\n"), {}, Cell::Purpose::Check);
  std::set<std::string> claimed = {"cell", "plc", "signals", "simulation", "registers"};  // the core's
  for (const auto& x : cell.soft().extensions())
    for (const auto& s : x->sections()) EXPECT_TRUE(claimed.insert(s).second) << s << " claimed twice";
  std::string listed;
  try {
    parse_cell_config("bogus: 1\n", "cell.yaml", Cell::sections());
  } catch (const SourceError& e) {
    listed = e.diagnostics().at(0).message;
  }
  std::string expected;
  for (const auto& s : claimed) expected += (expected.empty() ? "" : ", ") + s;
  EXPECT_NE(listed.find("(expected one of: " + expected + ")"), std::string::npos) << listed;
}

TEST(Extensions, CountersAndAxesReportTheirState) {
  TempDir d;
  const std::string cfg = write_cell(d,
                                     "counters:\n  hsc0: {mode: MD7, name: belt}\n"
                                     "axes:\n  pso0: {name: lift}\n",
                                     "ORG M1925\nOUT Y10\nEND\n");
  Cell cell(cfg, {}, Cell::Purpose::Check);
  std::map<std::string, std::vector<ExtensionStatus>> by;
  for (const auto& x : cell.soft().extensions()) by[x->name()] = x->status(cell.plc());
  ASSERT_EQ(by["counters"].size(), 1u);
  EXPECT_EQ(by["counters"][0].message, "1 counter configured");
  EXPECT_EQ(by["counters"][0].values, (std::vector<std::pair<std::string, std::string>>{{"belt", "0"}}));
  ASSERT_EQ(by["axes"].size(), 1u);
  EXPECT_EQ(by["axes"][0].name, "axis lift");
  EXPECT_EQ(by["axes"][0].message, "idle");
  EXPECT_EQ(by["axes"][0].level, ExtensionStatus::Level::Ok);
  EXPECT_TRUE(by["modules"].empty());
}
