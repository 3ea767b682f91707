#include "mutate_option.h"

#include <fstream>
#include <iostream>

#include "plc_cell/core/error.h"
#include "plc_cell/mutation/mutation_report.h"
#include "scenario_files.h"

namespace plc_cell {
namespace cli {

void run_mutate(const Args& args, const std::vector<scenario::Scenario>& files, std::optional<EngineChoice> engine,
                std::string* html) {
  mutation::Options o;
  o.budget = size_t(args.get_int("mutate-budget", 0, 0, 1000000));
  o.jobs = int(args.get_int("jobs", 1, 1, 64));
  // Many runs of the same cases: the native engine unless --engine says otherwise.
  const EngineChoice e = engine.value_or(EngineChoice::Native);
  const auto results = mutation::run_mutation(files, o, mutation_targets(e));
  std::cout << "mutation testing on the " << engine_choice_name(e)
            << " engine (the original program's cases on the interpreter, recording what they execute)\n";
  std::cout.flush();
  mutation::write_text(results, std::cout);
  if (args.has("mutate-json")) {
    std::ofstream out(args.get("mutate-json"));
    if (!out) throw Error("cannot write the mutation file " + args.get("mutate-json"));
    mutation::write_json(results, out);
  }
  *html = mutation::html_section(results);
}

}  // namespace cli
}  // namespace plc_cell
