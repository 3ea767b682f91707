#include "scenario_files.h"

#include <iostream>
#include <sstream>

#include "plc_cell/config/error_list.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace plc_cell {
namespace cli {

namespace {

// The explore section's inputs: each drivable on the cell, its low and high values taken.
void check_explore(const scenario::Scenario& sc, scenario::Target& target, ErrorList& errors) {
  for (const auto& d : sc.explore.inputs) {
    auto error = [&](const std::string& why) {
      Diagnostic e;
      e.where.file = sc.file;
      e.where.line = d.line;
      e.message = "key 'explore.inputs." + d.probe.text + "': " + why;
      errors.add(e);
    };
    const std::string why = target.check(d.probe, true);
    if (!why.empty()) {
      error(why);
      continue;
    }
    for (double v : {d.lo, d.hi}) {
      scenario::Value value;
      value.number = v;
      value.text = std::to_string(int64_t(v));
      try {
        target.write(d.probe, value);
      } catch (const Error& e) {
        error(e.what());
        break;
      }
    }
  }
}

}  // namespace

bool load_scenarios(const std::vector<std::string>& paths, const std::string& tool,
                    std::vector<scenario::Scenario>* files) {
  ErrorList errors;
  for (const auto& path : paths) {
    files->push_back(scenario::read_scenario(path, errors));
    const scenario::Scenario& sc = files->back();
    if (sc.cell.empty() && sc.line.empty()) continue;
    errors.collect([&] {
      FreshTarget fresh(sc, std::nullopt);
      scenario::Target& target = fresh.target();
      scenario::Case props;  // the properties, for a file with no case
      props.properties = sc.properties;
      for (const auto& e : scenario::check_case(props, target)) errors.add(e);
      for (const auto& c : sc.cases)
        for (const auto& e : scenario::check_case(c, target)) errors.add(e);
      check_explore(sc, target, errors);
    }, path);
  }
  if (errors.empty()) return true;
  try {
    errors.throw_if_any();  // sorted: file by file, by line
  } catch (const SourceError& e) {
    for (const auto& d : e.diagnostics()) std::cerr << d.to_string() << "\n";
  }
  std::cerr << tool << ": " << errors.size() << " error(s) in the scenario files; no case ran\n";
  return false;
}

void print_result(const scenario::Scenario& sc, const scenario::CaseResult& r, const std::string& time) {
  std::cout << (r.passed ? "PASS  " : "FAIL  ") << sc.file << ": " << r.name << "  (" << time << ")\n";
  if (r.passed) return;
  std::cout << "    " << r.failure << "\n";
  std::istringstream details(r.details);
  for (std::string line; std::getline(details, line);) std::cout << "    " << line << "\n";
}

std::optional<EngineChoice> engine_option(const Args& args) {
  if (!args.has("engine")) return std::nullopt;
  EngineChoice engine{};
  if (!parse_engine_choice(args.get("engine"), &engine))
    throw UsageError("--engine " + args.get("engine") + ": expected native, interpreter or lockstep");
  return engine;
}


}  // namespace cli
}  // namespace plc_cell
