// The change service (docs/online-change.md) on the demo conveyor, served in real time: a
// change that breaks the interlock property is refused with the property's report and the
// running program untouched; the part counter's preset passes the gate and goes live without
// a scan missed; Undo restores; every attempt is in the audit trail, which a restart reads
// back; the program file is rewritten only for the page and the service.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <fstream>
#include <sstream>

#include "plc_cell/online/il_diff.h"
#include "plc_cell/online/program_watch.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void spit(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string replace(std::string s, const std::string& from, const std::string& to) {
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) s.replace(at, from.size(), to);
  return s;
}

// The demo's files copied into a folder of this test's own: the service writes beside them.
class DemoCell : public ::testing::Test {
 protected:
  void SetUp() override {
    char d[] = "/tmp/online_test.XXXXXX";
    ASSERT_NE(mkdtemp(d), nullptr);
    dir = d;
    const std::string src = std::string(PLC_CELL_SOURCE_DIR) + "/examples/conveyor/";
    for (const char* f : {"conveyor.yaml", "conveyor.il", "conveyor.scenario.yaml"}) spit(dir + "/" + f, slurp(src + f));
    original = slurp(dir + "/conveyor.il");
    setenv("PLC_CELL_TOOL", PLC_CELL_TOOL, 1);  // the gate's process: the tool of this build
  }
  void TearDown() override {
    cell.reset();
    std::string cmd = "rm -rf " + dir;
    ASSERT_EQ(std::system(cmd.c_str()), 0);
  }
  void serve() {
    cell = std::make_unique<Cell>(dir + "/conveyor.yaml", CellOverrides{}, Cell::Purpose::Serve);
    ASSERT_TRUE(cell->plc().set_mode(RunMode::Run));
    cell->start_scanning();
  }
  uint64_t scans() {
    return cell->plc().locked([](ScanEngine& e, Memory&) { return e.stats().scans; });
  }
  int64_t counter_preset() {
    return cell->plc().locked([](ScanEngine& e, Memory&) {
      for (const auto& in : e.program().code)
        if (in.op == Op::Ctr) return in.operands.at(0).k;
      return int64_t(-1);
    });
  }
  ChangeOutcome apply(const std::string& text, ChangeSource source = ChangeSource::Page, bool force = false,
                      const std::string& reason = "") {
    ChangeRequest r;
    r.text = text;
    r.source = source;
    r.force = force;
    r.reason = reason;
    return cell->changes().apply(r);
  }

  std::string dir, original;
  std::unique_ptr<Cell> cell;
};

TEST_F(DemoCell, AChangeThatBreaksTheInterlockIsRefusedWithThePropertysReport) {
  serve();
  const std::string broken = replace(original, "OR      Y1\nANDLD", "OR      Y2\nANDLD");
  const uint64_t before = scans();
  const ChangeOutcome o = apply(broken);
  EXPECT_EQ(o.result, "refused");
  EXPECT_NE(o.why.find("the gate failed"), std::string::npos) << o.why;
  ASSERT_TRUE(o.gate.configured);
  EXPECT_FALSE(o.gate.passed);
  const std::string report = o.gate.report.dump();
  EXPECT_NE(report.find("property always: pick_request -> not conveyor_run violated"), std::string::npos) << report;
  EXPECT_EQ(slurp(dir + "/conveyor.il"), original) << "the file is not rewritten for a refused change";
  EXPECT_EQ(cell->changes().hash(), online::text_hash(original));
  EXPECT_EQ(counter_preset(), 9999);
  EXPECT_GT(scans(), before) << "the cell scanned on while the gate ran";
  const auto log = cell->changes().log(10);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0]["result"], "refused");
  EXPECT_EQ(log[0]["source"], "page");
  EXPECT_NE(log[0]["diff"].get<std::string>().find("+OR      Y2"), std::string::npos);
}

TEST_F(DemoCell, TheCountersPresetGoesLiveWithoutAMissedScanAndUndoRestoresIt) {
  serve();
  const std::string harmless = replace(original, "CTR     C0 9999", "CTR     C0 5000");
  const uint64_t before = scans();
  const uint64_t loads = cell->plc().locked([](ScanEngine& e, Memory&) { return e.program_loads(); });
  const ChangeOutcome o = apply(harmless);
  ASSERT_EQ(o.result, "applied") << o.why << " " << o.gate.summary;
  EXPECT_TRUE(o.gate.passed);
  EXPECT_EQ(counter_preset(), 5000);
  // Not a timing claim (the machine may be loaded): the cell scanned on in RUN while the gate
  // ran in its own process, and the program was swapped once, between two scans.
  EXPECT_GT(scans(), before);
  EXPECT_EQ(cell->plc().mode(), RunMode::Run);
  EXPECT_EQ(cell->plc().locked([](ScanEngine& e, Memory&) { return e.program_loads(); }), loads + 1);
  EXPECT_TRUE(cell->plc().locked([](ScanEngine& e, Memory&) { return e.last_load_online(); }));
  EXPECT_EQ(slurp(dir + "/conveyor.il"), harmless) << "a change from the page rewrites the program file";
  EXPECT_EQ(slurp(dir + "/conveyor.il.versions/" + online::text_hash(original) + ".il"), original)
      << "the previous version is kept";
  const ChangeOutcome u = cell->changes().undo(ChangeSource::Page);
  ASSERT_EQ(u.result, "applied") << u.why;
  EXPECT_TRUE(u.undo);
  EXPECT_EQ(counter_preset(), 9999);
  EXPECT_EQ(slurp(dir + "/conveyor.il"), original);
  EXPECT_EQ(cell->changes().undo(ChangeSource::Page).why, "no applied change to undo");
}

TEST_F(DemoCell, TheAuditTrailSurvivesARestartAndUndoWorksAfterIt) {
  serve();
  ASSERT_EQ(apply(replace(original, "CTR     C0 9999", "CTR     C0 4000"), ChangeSource::Service).result, "applied");
  ASSERT_EQ(apply("ORG X0\nOUT Y0\nFUN 999\nEND\n").result, "refused");
  cell.reset();
  serve();  // the same files, a new process's view of them
  const auto log = cell->changes().log(10);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0]["result"], "applied");
  EXPECT_EQ(log[0]["source"], "service");
  EXPECT_EQ(log[0]["old_hash"], online::text_hash(original));
  EXPECT_EQ(log[1]["result"], "refused");
  EXPECT_FALSE(log[1]["errors"].empty());
  EXPECT_EQ(log[1]["errors"][0]["line"], 3);
  const ChangeOutcome u = cell->changes().undo(ChangeSource::Page);
  EXPECT_EQ(u.result, "applied") << u.why;
  EXPECT_EQ(slurp(dir + "/conveyor.il"), original);
}

TEST_F(DemoCell, ApplyAnywayNeedsAReasonAndIsLoggedAsForced) {
  serve();
  const std::string broken = replace(original, "OR      Y1\nANDLD", "OR      Y2\nANDLD");
  EXPECT_EQ(apply(broken, ChangeSource::Page, true, "").why, "apply anyway needs a reason");
  const ChangeOutcome o = apply(broken, ChangeSource::Page, true, "robot removed for maintenance");
  EXPECT_EQ(o.result, "forced") << o.why;
  const auto log = cell->changes().log(10);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[1]["result"], "forced");
  EXPECT_EQ(log[1]["reason"], "robot removed for maintenance");
}

TEST_F(DemoCell, ASavedFileGoesLiveThroughTheSamePathAndIsNeverRewritten) {
  serve();
  std::vector<ChangeOutcome> seen;
  online::ProgramWatch watch(cell->changes(), [&](const ChangeOutcome& o) { seen.push_back(o); }, 3'600'000'000ull);
  const std::string harmless = replace(original, "CTR     C0 9999", "CTR     C0 5000");
  spit(dir + "/conveyor.il", harmless);
  ASSERT_TRUE(watch.poll());
  ASSERT_EQ(seen.size(), 1u);
  EXPECT_EQ(seen[0].result, "applied") << seen[0].why;
  EXPECT_EQ(counter_preset(), 5000);
  EXPECT_FALSE(watch.poll()) << "the running program's own text is no change";
  const std::string bad = harmless + "FUN 999\n";
  spit(dir + "/conveyor.il", bad);
  ASSERT_TRUE(watch.poll());
  EXPECT_EQ(seen.back().result, "refused");
  EXPECT_FALSE(watch.poll()) << "a refused text is tried again only once saved anew";
  EXPECT_EQ(slurp(dir + "/conveyor.il"), bad) << "a change from the file never rewrites it";
  const auto log = cell->changes().log(10);
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0]["source"], "file");
}

TEST(ChangedLines, TheLinesOfTheNewTextNotInTheOld) {
  const std::string old = "ORG X0\nOUT Y0\nORG X1\nOUT Y1\nEND\n";
  EXPECT_TRUE(online::changed_lines(old, old).empty());
  EXPECT_EQ(online::changed_lines(old, "ORG X0\nOUT Y0\nORG X2\nOUT Y1\nEND\n"), std::vector<int>{3});
  EXPECT_EQ(online::changed_lines(old, "ORG X0\nOUT Y0\nORG X5\nOUT M5\nORG X1\nOUT Y1\nEND\n"),
            (std::vector<int>{3, 4}));
  EXPECT_TRUE(online::changed_lines(old, "ORG X0\nOUT Y0\nEND\n").empty()) << "a deletion writes no line";
  EXPECT_EQ(online::changed_lines("", "ORG X0\nEND\n"), (std::vector<int>{1, 2}));
}

// gate.mutate: true on the demo: the mutants of the lines a change wrote must be killed by
// the cases (or be equivalent-suspect: no case and no input search tells them apart).
class DemoCellMutating : public DemoCell {
 protected:
  void SetUp() override {
    DemoCell::SetUp();
    const std::string yaml = slurp(dir + "/conveyor.yaml");
    spit(dir + "/conveyor.yaml", replace(yaml, "  explore: 20s\n", "  explore: 20s\n  mutate: true\n"));
  }
};

TEST_F(DemoCellMutating, AChangeNoCaseChecksIsRefusedNamingItsSurvivingMutants) {
  serve();
  // A new network: nothing breaks, and no case looks at M500.
  const std::string untested = replace(original, "END", "ORG     X3\nOUT     M500\nEND");
  const int first = int(std::count(original.begin(), original.begin() + original.find("END"), '\n')) + 1;
  const ChangeOutcome o = apply(untested);
  EXPECT_EQ(o.result, "refused") << o.gate.summary;
  ASSERT_TRUE(o.gate.configured);
  EXPECT_FALSE(o.gate.passed);
  EXPECT_NE(o.gate.summary.find("mutant(s) of the changed lines survived"), std::string::npos) << o.gate.summary;
  const auto& m = o.gate.report.at("mutation");
  EXPECT_EQ(m.at("lines"), (std::vector<int>{first, first + 1}));
  ASSERT_FALSE(m.at("survived").empty()) << m.dump();
  for (const auto& s : m.at("survived")) {
    const int line = s.at("line").get<int>();
    EXPECT_TRUE(line == first || line == first + 1) << s.dump();
  }
  EXPECT_EQ(cell->changes().hash(), online::text_hash(original)) << "the running program is kept";
  EXPECT_EQ(o.gate.since, online::text_hash(original));
}

TEST_F(DemoCellMutating, AChangeWhoseMutantsNothingTellsApartPasses) {
  serve();
  // The counter's preset: its mutants (+1, -1, x2, /2) are not reached in any case or search.
  const std::string harmless = replace(original, "CTR     C0 9999", "CTR     C0 5000");
  const GateResult g = cell->changes().test(harmless);
  ASSERT_TRUE(g.passed) << g.summary << " " << g.report.dump();
  const auto& m = g.report.at("mutation");
  const int line = int(std::count(original.begin(), original.begin() + original.find("CTR     C0"), '\n')) + 1;
  EXPECT_EQ(m.at("lines"), std::vector<int>{line});
  EXPECT_EQ(m.at("mutants"), 4);
  EXPECT_EQ(m.at("equivalent"), 4);
  EXPECT_TRUE(m.at("survived").empty());
}

}  // namespace
}  // namespace plc_cell
