// plc_cell gate: the tests a cell's YAML names in its gate: section, run on a program in
// virtual time: every case of every named scenario file (their properties checked after
// every scan), with gate.explore, a bounded exploration of each file's explore inputs, and,
// with gate.mutate, mutation testing of the lines the change wrote (--since: the running
// program). The change service runs it as a process of its own before a change goes live
// (docs/online-change.md); --json is the report it reads.
#include <chrono>
#include <iostream>

#include <nlohmann/json.hpp>

#include "args.h"
#include "commands.h"
#include "fresh_target.h"
#include "scenario_files.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/explore/explorer.h"
#include "plc_cell/config/gate_config.h"
#include "plc_cell/mutation/mutation_report.h"
#include "plc_cell/online/il_diff.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace cli {

namespace {

using nlohmann::json;

struct GateRun {
  json cases = json::array(), explore = json::array(), mutation;
  size_t passed = 0, failed = 0, violations = 0, survivors = 0;
  uint64_t virtual_us = 0;
};

void run_cases(const std::vector<scenario::Scenario>& files, const std::string& program, GateRun* g) {
  for (const auto& sc : files)
    for (const auto& c : sc.cases) {
      FreshTarget target(sc, std::nullopt, program);
      const scenario::CaseResult r = scenario::run_case(c, target.target());
      g->virtual_us += r.virtual_us;
      (r.passed ? g->passed : g->failed)++;
      g->cases.push_back({{"file", sc.file},           {"name", r.name},       {"line", r.line},
                          {"passed", r.passed},        {"failure", r.failure}, {"details", r.details},
                          {"virtual_s", r.virtual_us / 1e6}});
    }
}

// Each file's explore inputs at random against its properties, gate.explore of virtual time
// per file, from the file's own seed: the same change gets the same verdict.
void run_explore(std::vector<scenario::Scenario>& files, const std::string& program, uint64_t budget_us,
                 GateRun* g) {
  for (auto& sc : files) {
    if (!sc.explore.line || sc.explore.run_us == 0) continue;
    sc.explore.budget_us = budget_us;
    const auto period = FreshTarget(sc, std::nullopt, program).target().period_us();
    const explore::Runner runner = [&](const explore::InputRun& run) {
      FreshTarget target(sc, std::nullopt, program);
      return scenario::run_case(explore::as_case(sc, run, "gate explore"), target.target());
    };
    const explore::Outcome o = explore::explore(sc.explore, period, runner);
    g->virtual_us += o.virtual_us;
    g->violations += o.found;
    g->explore.push_back({{"file", sc.file}, {"seed", sc.explore.seed}, {"runs", o.runs},
                          {"virtual_s", o.virtual_us / 1e6}, {"violated", o.found}, {"failure", o.failure}});
  }
}

std::string read_text(const std::string& path) {
  std::optional<std::string> text = file_text(path);
  if (!text) throw Error("cannot read the program " + path);
  return std::move(*text);
}

// gate.mutate: the mutants of the lines the change wrote (since: the running program; ""
// every line), each on every case of the files; one that passes them all and is not
// equivalent-suspect survived, and fails the gate: no case tells the change from a slip of
// the pen in it. Cases that fail already fail the gate, and leave nothing to measure.
void run_mutants(const std::vector<scenario::Scenario>& files, const std::string& program, const std::string& since,
                 GateRun* g) {
  mutation::Options o;
  json lines = "every line";
  if (!since.empty()) {
    const std::vector<int> changed = online::changed_lines(read_text(since), read_text(program));
    lines = changed;
    o.lines.insert(changed.begin(), changed.end());
    if (changed.empty()) {
      g->mutation = {{"lines", lines}, {"mutants", 0}, {"killed", 0}, {"equivalent", 0}, {"survived", json::array()}};
      return;
    }
  }
  const mutation::TargetFactory base = mutation_targets(EngineChoice::Native);
  const mutation::TargetFactory make = [&](const scenario::Scenario& sc, const std::string& p, const std::string& r) {
    return base(sc, p.empty() ? program : p, r);
  };
  size_t mutants = 0, killed = 0, equivalent = 0;
  json survived = json::array();
  for (const mutation::ProgramResult& p : mutation::run_mutation(files, o, make))
    for (const mutation::MutantResult& r : p.results) {
      ++mutants;
      killed += r.verdict == mutation::Verdict::Killed;
      equivalent += r.verdict == mutation::Verdict::Equivalent;
      if (r.verdict != mutation::Verdict::Survived) continue;
      survived.push_back({{"line", r.mutant.line},
                          {"change", r.mutant.change()},
                          {"why", mutation::survival_name(mutation::survival(p, r))},
                          {"told_apart", r.told_apart}});
    }
  g->survivors = survived.size();
  g->mutation = {{"lines", lines},   {"mutants", mutants},       {"killed", killed},
                 {"equivalent", equivalent}, {"survived", survived}};
}

std::string summary_of(const GateRun& g, bool explored) {
  std::string s = std::to_string(g.passed) + " case(s) passed, " + std::to_string(g.failed) + " failed";
  if (explored)
    s += g.violations ? ", explore: a property violated" : ", explore: no property violated";
  if (!g.mutation.is_null())
    s += ", mutation: " + std::to_string(g.survivors) + " of " + std::to_string(g.mutation["mutants"].get<size_t>()) +
         (g.mutation["lines"].is_string() ? " mutant(s) survived" : " mutant(s) of the changed lines survived");
  return s;
}

void print_text(const GateRun& g, const std::string& summary) {
  for (const auto& c : g.cases) {
    std::cout << (c["passed"].get<bool>() ? "PASS  " : "FAIL  ") << c["file"].get<std::string>() << ": "
              << c["name"].get<std::string>() << "\n";
    if (!c["passed"].get<bool>()) std::cout << "    " << c["failure"].get<std::string>() << "\n";
  }
  for (const auto& e : g.explore) {
    std::cout << (e["violated"].get<bool>() ? "FAIL  " : "PASS  ") << "explore " << e["file"].get<std::string>()
              << ": " << e["runs"].get<uint64_t>() << " run(s)\n";
    if (e["violated"].get<bool>()) std::cout << "    " << e["failure"].get<std::string>() << "\n";
  }
  if (!g.mutation.is_null())
    for (const auto& m : g.mutation["survived"])
      std::cout << "FAIL  mutant line " << m["line"].get<int>() << ": " << m["change"].get<std::string>()
                << ": survived (" << m["why"].get<std::string>() << ")\n"
                << (m["told_apart"].get<std::string>().empty() ? "" : "    " + m["told_apart"].get<std::string>() + "\n");
  std::cout << "== gate: " << summary << "\n";
}

}  // namespace

int cmd_gate(const std::vector<std::string>& argv) {
  Args args(argv, {"program", "since"}, {"json"});
  if (args.positional().size() != 1) throw UsageError("gate takes one cell YAML");
  const auto t0 = std::chrono::steady_clock::now();
  CellOverrides o;
  o.program = args.get("program");
  GateConfig gate;
  std::string program;  // the file the gate tests: --program, or the cell's own
  {
    Cell cell(args.positional()[0], o, Cell::Purpose::Check);  // the program's errors, at their lines
    if (const auto* g = cell.soft().get<GateConfig>()) gate = *g;
    program = cell.program_path();
  }
  if (!gate.line) throw Error(args.positional()[0] + ": no gate: section names the tests a change must pass");
  std::vector<scenario::Scenario> files;
  if (!load_scenarios(gate.scenarios, "plc_cell gate", &files)) return 2;
  GateRun g;
  run_cases(files, o.program, &g);
  if (gate.explore_us) run_explore(files, o.program, gate.explore_us, &g);
  if (gate.mutate && g.failed == 0) run_mutants(files, program, args.get("since"), &g);
  const bool passed = g.failed == 0 && g.violations == 0 && g.survivors == 0;
  const std::string summary = summary_of(g, gate.explore_us != 0);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (args.has("json")) {
    json report{{"passed", passed},   {"summary", summary},        {"program", o.program},
                {"cases", g.cases},   {"explore", g.explore},      {"virtual_s", g.virtual_us / 1e6},
                {"wall_s", wall}};
    if (!g.mutation.is_null()) report["mutation"] = g.mutation;
    std::cout << report.dump() << "\n";
  } else {
    print_text(g, summary);
  }
  return passed ? 0 : 1;
}

Command gate_command() {
  return {"gate",
          "CELL.yaml [--program FILE] [--since FILE] [--json]  run the tests the cell's gate:\n"
          "         section names (its scenarios' cases and properties, a bounded exploration,\n"
          "         mutation testing of the lines changed since FILE) on the program, as a\n"
          "         change in RUN must pass them (docs/online-change.md)\n",
          cmd_gate};
}

}  // namespace cli
}  // namespace plc_cell
