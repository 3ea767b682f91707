#pragma once
// Mutation testing (docs/testing-your-cell.md, "Mutation testing"): every case of the
// scenario files against every mutant of their programs, each on a fresh cell in virtual
// time. A mutant is killed when a case fails (a fault fails it too). One that passes every
// case is equivalent-suspect only when no case saw an observed value differ from the
// original program's and a search over the inputs finds no difference either
// (input_search.h); every other one survived.
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/mutation/mutant.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace mutation {

enum class Verdict { Killed, Survived, Equivalent, NotLoaded };
const char* verdict_name(Verdict v);  // "killed", "survived", "equivalent-suspect", "not loaded"

struct MutantResult {
  Mutant mutant;
  Verdict verdict = Verdict::Survived;
  std::string killed_by;   // the first case that failed
  bool observed = false;   // survived: a case saw an observed value differ
  std::string told_apart;  // survived, no case saw it: the input search's first difference
  std::string searched;    // equivalent-suspect: what the search tried
};

struct NetworkSpan {
  uint32_t number = 0;
  int line = 0, end_line = 0;
};

struct ProgramResult {
  std::string program;  // the program file
  size_t cases = 0;     // the cases run on each mutant
  size_t generated = 0; // the mutants before the budget
  std::vector<NetworkSpan> networks;
  std::vector<MutantResult> results;                      // in line order
  std::map<int, std::vector<std::string>> executed_by;  // line: the cases that executed it
};

struct Options {
  size_t budget = 0;  // at most this many mutants per program (0: all), evenly spaced
  // Only the mutants of these lines of the program (empty: every line), before the budget:
  // the lines a change wrote, when a gate asks whether the cases test the change.
  std::set<int> lines;
  int jobs = 1;       // worker processes
};

// What one case of a mutant runs on: a fresh target (a lone cell, or a line of cells:
// docs/lines.md) and in it the cells that run the program under test, each with the
// prefix under which the scenario names its memory ("" for a lone cell, "robot." in a line).
struct Subject {
  struct Part {
    Cell* cell = nullptr;
    std::string prefix;
  };
  scenario::Target* target = nullptr;
  std::vector<Part> cells;
  std::vector<std::string> programs;  // every program file the target runs, in its cells' order
  std::shared_ptr<void> owner;        // what keeps target and cells alive
};

// A fresh target of sc for one case: program, one of the files it runs ("": its first),
// replaced by replacement ("": none) in every cell that runs it, and those cells in cells.
using TargetFactory = std::function<Subject(const scenario::Scenario& sc, const std::string& program,
                                            const std::string& replacement)>;

// Throws plc_cell::Error when a case fails on the original program (nothing to measure).
std::vector<ProgramResult> run_mutation(const std::vector<scenario::Scenario>& files, const Options& options,
                                        const TargetFactory& make);

}  // namespace mutation
}  // namespace plc_cell
