// plc_cell explore: the file's declared inputs driven at random against its properties, in
// virtual time; the first violation shrunk and written as a scenario case
// (docs/testing-your-cell.md, "Exploring").
#include <fstream>
#include <iostream>

#include "args.h"
#include "commands.h"
#include "plc_cell/core/error.h"
#include "plc_cell/explore/case_writer.h"
#include "plc_cell/explore/explorer.h"
#include "scenario_files.h"

namespace plc_cell {
namespace cli {

namespace {

std::string changes(size_t n) { return std::to_string(n) + (n == 1 ? " change" : " changes"); }

// The file the case goes to and what it says of where it came from.
void write_case(const Args& args, const scenario::Scenario& sc, const explore::Outcome& o) {
  const std::string seed = std::to_string(sc.explore.seed);
  const std::string out = args.get("out", "explore_seed" + seed + ".scenario.yaml");
  const std::string comment = "plc_cell explore " + sc.file + " (seed " + seed + "): run " +
                              std::to_string(o.found_in_run) + ", " + changes(o.original.changes.size()) +
                              ", shrunk to " + changes(o.shrunk.changes.size()) + "\n" + o.failure;
  std::ofstream f(out);
  if (!f) throw Error("cannot write the case file " + out);
  f << explore::case_file(sc, o.shrunk, "explore seed " + seed, out, comment);
  std::cout << "wrote " << out << ": plc_cell test " << out << " reproduces it\n";
}

}  // namespace

int cmd_explore(const std::vector<std::string>& argv) {
  Args args(argv, {"seed", "budget", "run", "out", "engine"});
  if (args.positional().size() != 1) throw UsageError("explore takes one scenario file");
  const std::optional<EngineChoice> engine = engine_option(args);
  std::vector<scenario::Scenario> files;
  if (!load_scenarios(args.positional(), "plc_cell explore", &files)) return 1;
  scenario::Scenario& sc = files[0];
  if (!sc.explore.line) {
    std::cerr << sc.file << ": error: no 'explore:' section: nothing says which inputs to drive\n";
    return 1;
  }
  if (args.has("seed")) sc.explore.seed = uint64_t(args.get_int("seed", 1, 0, 2147483647));
  try {
    if (args.has("run")) sc.explore.run_us = parse_duration_us(args.get("run"));
    if (args.has("budget")) sc.explore.budget_us = parse_duration_us(args.get("budget"));
  } catch (const Error& e) {
    throw UsageError(std::string("--run/--budget: ") + e.what());
  }
  if (sc.explore.run_us == 0) throw UsageError("--run 0: a run of 0 s explores nothing");
  const auto period = fresh_target(sc, engine)->target().period_us();
  const explore::Runner runner = [&](const explore::InputRun& run) {
    const auto target = fresh_target(sc, engine);  // a fresh cell (or line) for every run
    return scenario::run_case(explore::as_case(sc, run, "explore"), target->target());
  };
  const explore::Outcome o = explore::explore(sc.explore, period, runner);
  std::cout << "explore " << sc.file << ": seed " << sc.explore.seed << ", " << o.runs << " run(s), "
            << scenario::format_time(o.virtual_us) << " of virtual time\n";
  if (!o.found) {
    std::cout << "no property violated\n";
    return 0;
  }
  std::cout << "run " << o.found_in_run << " violated a property after " << changes(o.original.changes.size())
            << " (at " << scenario::format_time(o.original.end_us) << "); shrunk in " << o.shrink_runs
            << " runs to " << changes(o.shrunk.changes.size()) << " (at " << scenario::format_time(o.shrunk.end_us)
            << "):\n    " << o.failure << "\n";
  write_case(args, sc, o);
  return 1;
}

Command explore_command() {
  return {"explore",
          "FILE.scenario.yaml [--seed N] [--budget 100s] [--run 10s] [--out CASE.yaml]\n"
          "         [--engine E]  drive the file's explore inputs at random against its\n"
          "         properties; the first violation shrunk and written as a scenario case\n",
          cmd_explore};
}

}  // namespace cli
}  // namespace plc_cell
