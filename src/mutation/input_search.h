#pragma once
// The search that earns "equivalent-suspect" (docs/testing-your-cell.md, "Mutation
// testing"): when every case passes on a mutant and no case saw an observed value differ,
// the original and the mutant are driven with the same inputs, each on a fresh cell, and
// compared after every scan. First, where the mutant's network depends on few inputs
// (input_cone.h), every combination of them and every change from one to another; then
// random runs of the cell's inputs, as plc_cell explore makes them (the file's explore:
// domains where it has them). Bounded and deterministic: the same program and files give
// the same runs.
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "input_cone.h"
#include "plc_cell/explore/input_run.h"
#include "plc_cell/mutation/mutation_run.h"

namespace plc_cell {
namespace mutation {

// At most this many inputs: every combination is tried (2^4 = 16, 257 steps).
constexpr size_t kFewInputs = 4;
// The exhaustive run holds each step one scan, then again this long (timers, counters).
constexpr uint64_t kLongHoldUs = 1000000;
// Without an explore: section: every input the program reads, as a bit held one scan to
// kDefaultHoldUs, in kDefaultRuns runs of kDefaultRunUs from seed 1.
constexpr uint64_t kDefaultHoldUs = 1000000;
constexpr uint64_t kDefaultRunUs = 10000000;
constexpr uint64_t kDefaultRuns = 10;

// What a search found: the first observed value that differs.
struct Finding {
  bool found = false;
  std::string what;  // "Y1 ON, the original's OFF", "the PLC faults: ..."
  uint64_t at_us = 0;
  std::string run;   // "the exhaustive run over X2, X3 (one scan a step)", "exploration run 3 of 10"
  std::string text() const;  // "Y1 ON, the original's OFF at 0.004 s of ..."
};

// Every combination of k inputs and every change between two of them (each ordered pair
// once: 4^k changes), from all inputs off; each step held hold_us, on the scan grid.
explore::InputRun exhaustive_run(size_t k, uint64_t hold_us, uint64_t period_us);

class InputSearch {
 public:
  // sc: the file whose cell runs the search, with its explore: section if it has one;
  // observed: what is compared after every scan.
  InputSearch(const scenario::Scenario& sc, std::string original,
              const Program& program, const FunctionTable& functions, std::vector<scenario::Probe> observed,
              TargetFactory make);

  // The first run, in the order of plan(line), in which the mutant (a program file) differs.
  Finding tell_apart(const std::string& mutant, int line);
  // "every combination of X2, X3 (one scan a step, then 1 s), then 10 exploration runs of 10 s"
  std::string plan(int line) const;

 private:
  struct Stimulus {
    std::string name;
    scenario::ExploreSpec spec;  // the inputs it drives
    explore::InputRun run;
    std::vector<uint64_t> reference;  // the original's hash per scan, once it ran
  };
  using AfterScan = std::function<bool(size_t scan, const Subject& s)>;  // false: stop

  const NetworkInputs* network_of(int line) const;
  bool exhaustive(const NetworkInputs* n) const { return n && n->closed && n->x.size() <= kFewInputs; }
  std::vector<Stimulus>& exhaustive_stimuli(const NetworkInputs& n);
  void drive(const std::string& program, const Stimulus& s, const AfterScan& after);
  uint64_t scan_hash(const Subject& s);
  Finding compare(const std::string& mutant, Stimulus& s);
  std::string difference(const std::string& mutant, const Stimulus& s, size_t scan);

  scenario::Scenario sc_;
  std::string original_;
  std::vector<scenario::Probe> observed_;
  // The observed addresses of each of the subject's cells, read in one memory copy of the
  // cell after every scan; the other probes (counters, axes, other cells' names, ...)
  // through the target.
  std::vector<std::vector<Address>> addresses_;
  std::vector<scenario::Probe> others_;
  TargetFactory make_;
  Subject::Part input_;  // the cell whose inputs the search drives without an explore: section
  uint64_t period_us_ = 1000;
  std::vector<NetworkInputs> networks_;
  std::map<int, std::vector<Stimulus>> exhaustive_;  // by the network's line
  std::vector<Stimulus> exploration_;
  std::string exploration_plan_;
};

}  // namespace mutation
}  // namespace plc_cell
