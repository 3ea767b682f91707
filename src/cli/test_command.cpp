// plc_cell test: scenario files run in virtual time, each case on a fresh cell; one line
// per case, the failures in full, JUnit XML for CI, rung coverage summed over the cases
// (docs/testing-your-cell.md, docs/coverage.md).
#include <algorithm>
#include <fstream>
#include <iostream>
#include <memory>
#include <set>
#include <sstream>

#include "args.h"
#include "commands.h"
#include "mutate_option.h"
#include "record_option.h"
#include "scenario_files.h"
#include "target_run.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/core/error.h"
#include "plc_cell/coverage/recorders.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/junit.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace cli {

namespace {

bool selected(const std::vector<std::string>& filters, const std::string& name) {
  if (filters.empty()) return true;
  for (const auto& f : filters)
    if (name.find(f) != std::string::npos) return true;
  return false;
}

void write_outputs(const Args& args, const std::vector<scenario::CaseResult>& results,
                   const coverage::Recorders& recorders, bool coverage, const std::string& extra_html) {
  if (args.has("junit")) {
    std::ofstream out(args.get("junit"));
    if (!out) throw Error("cannot write the JUnit file " + args.get("junit"));
    scenario::write_junit(results, out);
  }
  if (!coverage) return;
  const std::vector<coverage::Report> reports = recorders.reports();
  if (args.has("coverage")) coverage::write_text(reports, std::cout);
  if (args.has("coverage-json")) {
    std::ofstream out(args.get("coverage-json"));
    if (!out) throw Error("cannot write the coverage file " + args.get("coverage-json"));
    coverage::write_json(reports, out);
  }
  if (args.has("coverage-html")) coverage::write_html(reports, args.get("coverage-html"), extra_html);
}

}  // namespace

int cmd_test(const std::vector<std::string>& argv_in) {
  // -k NAME, as pytest spells it, is --case NAME.
  std::vector<std::string> argv;
  for (const auto& a : argv_in) argv.push_back(a == "-k" ? "--case" : a == "-j" ? "--jobs" : a);
  std::vector<std::string> options = {"junit", "case", "coverage-json", "coverage-html", "engine", "mutate-budget",
                                      "mutate-json", "jobs", "record"};
  options.insert(options.end(), target_options().begin(), target_options().end());
  Args args(argv, options, {"coverage", "mutate", "dry-run"});
  if (args.positional().empty()) throw UsageError("no scenario file given");
  if (args.has("target") || args.has("dry-run")) return cmd_test_on_target(args);
  const std::optional<EngineChoice> engine = engine_option(args);  // else each cell's plc.engine
  const auto filters = args.all("case");
  // Every file read and checked before any case runs: all the errors of all the files at once.
  std::vector<scenario::Scenario> files;
  if (!load_scenarios(args.positional(), "plc_cell test", &files)) return 1;

  // Rung coverage, summed over every case of the run, per program.
  const bool coverage = args.has("coverage") || args.has("coverage-json") || args.has("coverage-html");
  coverage::Recorders recorders;
  std::vector<scenario::CaseResult> results;
  std::set<std::string> recorded;  // the recordings' file names
  uint64_t virtual_us = 0;
  for (const auto& sc : files)
    for (const auto& c : sc.cases) {
      if (!selected(filters, c.name)) continue;
      const auto target = fresh_target(sc, engine);  // a fresh cell (or line) for every case
      if (coverage)  // per program: a line's cells each add to their own program's coverage
        for (const auto& cell : target->cells()) recorders.attach(cell.second->plc(), cell.second->config().signals);
      const auto rec = args.has("record") ? record_case(*target, "plc_cell test " + sc.file + ": " + c.name) : nullptr;
      results.push_back(scenario::run_case(c, target->target()));
      if (coverage)
        for (const auto& cell : target->cells()) recorders.detach(cell.second->plc());
      virtual_us += results.back().virtual_us;
      print_result(sc, results.back(), scenario::format_time(results.back().virtual_us));
      if (rec) {
        const std::string path = save_case(*rec, results.back(), args.get("record"), &recorded);
        if (!results.back().passed) std::cout << "    recorded: " << monitor_command_for(path) << "\n";
      }
    }
  if (results.empty()) {
    std::cerr << "plc_cell test: no case matches -k";
    for (const auto& f : filters) std::cerr << " '" << f << "'";
    std::cerr << "\n";
    return 1;
  }
  size_t failed = 0;
  for (const auto& r : results) failed += !r.passed;
  std::cout << "== " << results.size() - failed << " passed, " << failed << " failed ("
            << scenario::format_time(virtual_us) << " of virtual time)\n";
  // Recording runs the interpreter whatever the cell's engine: the user must not take the
  // run for one on the native engine.
  if (coverage) std::cout << "coverage: every case ran on the interpreter's recording loop\n";
  // Mutants only of programs whose cases all pass: a failing case would kill every one.
  std::string mutation_html;
  if (args.has("mutate") && !failed) {
    std::vector<scenario::Scenario> chosen = files;  // the cases -k selects
    for (auto& sc : chosen)
      sc.cases.erase(std::remove_if(sc.cases.begin(), sc.cases.end(),
                                    [&](const scenario::Case& c) { return !selected(filters, c.name); }),
                     sc.cases.end());
    run_mutate(args, chosen, engine, &mutation_html);
  }
  if (args.has("mutate") && failed) std::cout << "no mutation testing: a case fails on the program itself\n";
  write_outputs(args, results, recorders, coverage, mutation_html);
  return failed ? 1 : 0;
}

Command test_command() {
  return {"test",
          "FILE.scenario.yaml... [-k NAME] [--junit OUT.xml] [--coverage]\n"
          "         [--coverage-json OUT.json] [--coverage-html DIR] [--engine E]\n"
          "         [--mutate [--mutate-budget N] [--mutate-json OUT.json] [-j N]] [--record DIR]\n"
          "         run the scenarios' test cases in virtual time, each on a fresh cell;\n"
          "         rung coverage summed over the cases; mutation testing of the programs;\n"
          "         --record: each case's run in DIR/<case>.plcrec (docs/recordings.md)\n"
          "         FILE.scenario.yaml... --target TARGET [--station N | --id N] [--tolerance T]\n"
          "         [--dry-run] [--timeout T] [--retries N] [--restore-timeout T] [-k NAME]\n"
          "         [--junit OUT.xml] [--record DIR]   the cases on a PLC over its link in wall-clock\n"
          "         time, leaving it as found; TARGET: fatek://HOST:PORT, fatek-serial:DEV[:BAUD[:FMT]],\n"
          "         tri://HOST:PORT, tri-serial:DEV[...], modbus://HOST:PORT, modbus-rtu:DEV[...]\n"
          "         (docs/testing-on-hardware.md)\n",
          cmd_test};
}

}  // namespace cli
}  // namespace plc_cell
