#include "input_search.h"

#include <algorithm>
#include <set>

#include "plc_cell/explore/explorer.h"
#include "plc_cell/scenario/runner.h"
#include "tracing_target.h"

namespace plc_cell {
namespace mutation {

namespace {

std::string hold_text(uint64_t hold_us, uint64_t period_us) {
  return hold_us == period_us ? "one scan" : scenario::format_time(hold_us);
}

// "X2, X3" (in a line "test.X2, test.X3").
std::string inputs_text(const std::string& prefix, const std::vector<uint32_t>& x) {
  std::string s;
  for (uint32_t i : x) s += (s.empty() ? "" : ", ") + prefix + "X" + std::to_string(i);
  return s;
}

scenario::InputDomain bit_input(const Subject::Part& part, uint32_t x, uint64_t hold_min_us, uint64_t hold_max_us) {
  scenario::InputDomain d;
  d.probe = probe_of(part, "X" + std::to_string(x));
  d.hold_min_us = hold_min_us;
  d.hold_max_us = hold_max_us;
  return d;
}

// Every ordered pair of n steps once, starting at step 0: an Euler circuit of the complete
// graph with loops (Hierholzer), n^2 + 1 steps.
std::vector<size_t> every_change(size_t n) {
  std::vector<size_t> next(n, 0), stack{0}, circuit;
  while (!stack.empty()) {
    const size_t v = stack.back();
    if (next[v] < n) {
      stack.push_back(next[v]++);
    } else {
      circuit.push_back(v);
      stack.pop_back();
    }
  }
  std::reverse(circuit.begin(), circuit.end());
  return circuit;
}

}  // namespace

std::string Finding::text() const { return what + " at " + scenario::format_time(at_us) + " of " + run; }

explore::InputRun exhaustive_run(size_t k, uint64_t hold_us, uint64_t period_us) {
  const std::vector<size_t> steps = every_change(size_t(1) << k);
  explore::InputRun run;
  // Step i is seen from the scan at i * hold: set after the scan before it.
  for (size_t i = 1; i < steps.size(); ++i)
    for (size_t j = 0; j < k; ++j)
      if (((steps[i] ^ steps[i - 1]) >> j) & 1)
        run.changes.push_back({i * hold_us - period_us, j, double((steps[i] >> j) & 1)});
  run.end_us = steps.size() * hold_us - period_us;
  return run;
}

InputSearch::InputSearch(const scenario::Scenario& sc, std::string original, const Program& program,
                         const FunctionTable& functions, std::vector<scenario::Probe> observed, TargetFactory make)
    : sc_(sc), original_(std::move(original)), observed_(std::move(observed)), make_(std::move(make)) {
  const Subject first = make_(sc_, original_, "");
  input_ = first.cells.front();
  input_.cell = nullptr;  // only its prefix: the cell goes with first
  period_us_ = std::max<uint64_t>(1, first.target->period_us());
  addresses_.resize(first.cells.size());
  for (const auto& p : observed_) {
    size_t k = 0;
    while (k < first.cells.size() && first.cells[k].prefix != (p.cell.empty() ? "" : p.cell + ".")) ++k;
    if (p.kind == scenario::Probe::Kind::Address && k < first.cells.size())
      addresses_[k].push_back(first.cells[k].cell->config().resolve(p.name));
    else
      others_.push_back(p);
  }
  networks_ = network_inputs(program, functions);
  scenario::ExploreSpec spec = sc_.explore;
  if (!spec.line) {
    std::set<uint32_t> x;
    for (const auto& n : networks_) x.insert(n.x.begin(), n.x.end());
    spec = {};
    for (uint32_t i : x) spec.inputs.push_back(bit_input(input_, i, period_us_, kDefaultHoldUs));
    spec.run_us = kDefaultRunUs;
    spec.budget_us = kDefaultRuns * kDefaultRunUs;
  }
  const uint64_t runs = std::max<uint64_t>(1, (spec.budget_us + spec.run_us - 1) / spec.run_us);
  for (uint64_t r = 0; r < runs; ++r) {
    Stimulus s;
    s.name = "exploration run " + std::to_string(r + 1) + " of " + std::to_string(runs);
    s.spec = spec;
    s.run = explore::random_run(spec, explore::run_seed(spec, r), period_us_);
    exploration_.push_back(std::move(s));
  }
  std::string inputs;
  for (const auto& d : spec.inputs) inputs += (inputs.empty() ? "" : ", ") + d.probe.text;
  exploration_plan_ = std::to_string(runs) + " exploration runs of " + scenario::format_time(spec.run_us) + " (" +
                      (sc_.explore.line ? "the explore: section's inputs" : "inputs") + " " +
                      (inputs.empty() ? "none" : inputs) + ", seed " + std::to_string(spec.seed) + ")";
}

const NetworkInputs* InputSearch::network_of(int line) const {
  for (const auto& n : networks_)
    if (line >= n.line && line <= n.end_line) return &n;
  return nullptr;
}

std::vector<InputSearch::Stimulus>& InputSearch::exhaustive_stimuli(const NetworkInputs& n) {
  auto it = exhaustive_.find(n.line);
  if (it != exhaustive_.end()) return it->second;
  std::vector<Stimulus> out;
  for (uint64_t hold : {period_us_, std::max(period_us_, kLongHoldUs / period_us_ * period_us_)}) {
    Stimulus s;
    s.name = "the exhaustive run over " +
             (n.x.empty() ? std::string("no input") : inputs_text(input_.prefix, n.x)) + " (" +
             hold_text(hold, period_us_) + " a step)";
    for (uint32_t x : n.x) s.spec.inputs.push_back(bit_input(input_, x, hold, hold));
    s.run = exhaustive_run(n.x.size(), hold, period_us_);
    out.push_back(std::move(s));
  }
  return exhaustive_[n.line] = std::move(out);
}

std::string InputSearch::plan(int line) const {
  const NetworkInputs* n = network_of(line);
  if (!exhaustive(n)) return exploration_plan_;
  return "every combination of " + (n->x.empty() ? std::string("no input") : inputs_text(input_.prefix, n->x)) +
         " (one scan a step, then " +
         scenario::format_time(kLongHoldUs) + "), then " + exploration_plan_;
}

uint64_t InputSearch::scan_hash(const Subject& s) {
  uint64_t h = kHashStart;
  for (size_t k = 0; k < s.cells.size(); ++k)
    h = s.cells[k].cell->plc().locked([&](ScanEngine& e, Memory& m) {
      uint64_t x = e.fault().empty() ? h : ~h;
      for (const Address& a : addresses_[k]) x = (x ^ m.read(a)) * 1099511628211ULL;
      return x;
    });
  return fold(h, *s.target, others_);
}

void InputSearch::drive(const std::string& program, const Stimulus& s, const AfterScan& after) {
  const Subject subject = make_(sc_, original_, program == original_ ? "" : program);
  scenario::Target* target = subject.target;
  auto set = [&](size_t input, double v) {
    const scenario::InputDomain& d = s.spec.inputs[input];
    scenario::Value value;
    value.number = v;
    value.text = explore::value_text(d, v);
    target->set(d.probe, value);
  };
  for (size_t k = 0; k < s.spec.inputs.size(); ++k) set(k, s.spec.inputs[k].lo);
  size_t next = 0, scan = 0;
  for (uint64_t t = 0; t <= s.run.end_us; t += period_us_, ++scan) {
    target->scan(t);
    if (!after(scan, subject) || !target->fault().empty()) return;  // a fault stops the PLC: the run ends
    for (; next < s.run.changes.size() && s.run.changes[next].t_us <= t; ++next)
      set(s.run.changes[next].input, s.run.changes[next].value);
  }
}

Finding InputSearch::compare(const std::string& mutant, Stimulus& s) {
  if (s.reference.empty())
    drive(original_, s, [&](size_t, const Subject& t) {
      s.reference.push_back(scan_hash(t));
      return true;
    });
  size_t differs = s.reference.size();
  size_t scans = 0;
  drive(mutant, s, [&](size_t i, const Subject& t) {
    scans = i + 1;
    if (i < s.reference.size() && scan_hash(t) == s.reference[i]) return true;
    differs = i;
    return false;
  });
  if (differs == s.reference.size() && scans == s.reference.size()) return {};
  if (differs == s.reference.size()) differs = scans < s.reference.size() ? scans : differs;
  Finding f;
  f.found = true;
  f.at_us = uint64_t(differs) * period_us_;
  f.run = s.name;
  f.what = difference(mutant, s, differs);
  return f;
}

// What differs at the scan: the first observed value in the order they are read (an
// output by its bit), else the fault.
std::string InputSearch::difference(const std::string& mutant, const Stimulus& s, size_t scan) {
  struct At {
    std::vector<scenario::Reading> values;
    std::string fault;
  };
  auto at = [&](const std::string& program) {
    At a;
    drive(program, s, [&](size_t i, const Subject& t) {
      if (i < scan) return true;
      for (const auto& p : observed_) a.values.push_back(t.target->read(p));
      a.fault = t.target->fault();
      return false;
    });
    return a;
  };
  const At o = at(original_), m = at(mutant);
  if (m.fault != o.fault) return m.fault.empty() ? "the original faults: " + o.fault : "the PLC faults: " + m.fault;
  const Subject names = make_(sc_, original_, "");  // for the names of the outputs
  for (size_t k = 0; k < observed_.size() && k < o.values.size() && k < m.values.size(); ++k) {
    if (o.values[k].number == m.values[k].number) continue;
    const scenario::Probe& p = observed_[k];
    if (p.kind == scenario::Probe::Kind::Address && p.name.rfind("WY", 0) == 0) {  // an output word: its bit
      const auto a = uint32_t(o.values[k].number), b = uint32_t(m.values[k].number);
      int bit = 0;
      while (!(((a ^ b) >> bit) & 1)) ++bit;
      Subject::Part part;
      part.prefix = p.cell.empty() ? "" : p.cell + ".";
      const auto y = probe_of(part, "Y" + std::to_string(std::stoi(p.name.substr(2)) + bit));
      return names.target->label(y) + " " + ((b >> bit) & 1 ? "ON" : "OFF") + ", the original's " +
             ((a >> bit) & 1 ? "ON" : "OFF");
    }
    return names.target->label(p) + " " + m.values[k].text + ", the original's " + o.values[k].text;
  }
  return "the run ends at another scan";
}

Finding InputSearch::tell_apart(const std::string& mutant, int line) {
  const NetworkInputs* n = network_of(line);
  if (exhaustive(n))
    for (Stimulus& s : exhaustive_stimuli(*n)) {
      Finding f = compare(mutant, s);
      if (f.found) return f;
    }
  for (Stimulus& s : exploration_) {
    Finding f = compare(mutant, s);
    if (f.found) return f;
  }
  return {};
}

}  // namespace mutation
}  // namespace plc_cell
