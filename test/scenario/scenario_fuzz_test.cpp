// Hostile scenario files, generated: the example scenarios mutated at random (bytes
// flipped, lines dropped, duplicated or swapped, values replaced by odd ones). Whatever
// comes out, reading it either succeeds or lists errors that each name the file and a
// line; nothing crashes. What reads well is checked against its cell and run for a bounded
// number of scans, which must end in a result, never an exception.
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

using namespace plc_cell;
using namespace plc_cell::scenario;

namespace {

const std::string kSrc = PLC_CELL_SOURCE_DIR;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines_of(const std::string& t) {
  std::vector<std::string> v;
  std::istringstream in(t);
  for (std::string l; std::getline(in, l);) v.push_back(l);
  return v;
}

const char* const kOdd[] = {"", "-1", "1e300", "nan", "0x", "${x}", "[", "{", "]]", ":", "- -", "99999999999s",
                            "R99999", "axis..state", "counter.", "not", "and and", "+-", "5 kV", "\t", "~", "*a",
                            "&a", "!!binary x", "'", "\"", "0s", "18446744073709551616", "-0", "Y0 == on +- -1"};

std::string mutate(const std::string& text, std::mt19937& rng) {
  std::vector<std::string> ls = lines_of(text);
  const int edits = 1 + int(rng() % 4);
  for (int e = 0; e < edits && !ls.empty(); ++e) {
    const size_t i = rng() % ls.size();
    switch (rng() % 6) {
      case 0: ls.erase(ls.begin() + long(i)); break;
      case 1: ls.insert(ls.begin() + long(i), ls[rng() % ls.size()]); break;
      case 2: std::swap(ls[i], ls[rng() % ls.size()]); break;
      case 3: {  // a value replaced by an odd one
        const auto colon = ls[i].find(": ");
        if (colon != std::string::npos) ls[i] = ls[i].substr(0, colon + 2) + kOdd[rng() % (sizeof kOdd / sizeof *kOdd)];
        break;
      }
      case 4:
        if (!ls[i].empty()) ls[i][rng() % ls[i].size()] = char(32 + rng() % 95);
        break;
      default:
        if (!ls[i].empty()) ls[i].insert(rng() % ls[i].size(), kOdd[rng() % (sizeof kOdd / sizeof *kOdd)]);
    }
  }
  std::string out;
  for (const auto& l : ls) out += l + "\n";
  return out;
}

// The cell's scans, at most a budget of them: a mutated time may ask for hours.
class Bounded : public Target {
 public:
  Bounded(Target& t, uint64_t max_scans) : t_(t), left_(max_scans) {}
  uint64_t period_us() const override { return t_.period_us(); }
  void scan(uint64_t t) override {
    if (left_-- == 0) throw Error("scan budget spent");
    t_.scan(t);
  }
  std::string check(const Probe& p, bool w) override { return t_.check(p, w); }
  Reading read(const Probe& p) override { return t_.read(p); }
  void set(const Probe& p, const Value& v) override { t_.set(p, v); }
  void write(const Probe& p, const Value& v) override { t_.write(p, v); }
  void force(const Probe& p, bool on) override { t_.force(p, on); }
  void release(const Probe* p) override { t_.release(p); }
  void simulate(const Probe* p) override { t_.simulate(p); }
  std::string fault() override { return t_.fault(); }

 private:
  Target& t_;
  uint64_t left_;
};

}  // namespace

TEST(ScenarioFuzz, MutatedScenariosGiveErrorsWithLinesOrRunToAResult) {
  const std::vector<std::string> files = {kSrc + "/examples/conveyor/conveyor.scenario.yaml",
                                          kSrc + "/examples/hsc/count_up_stop.scenario.yaml",
                                          kSrc + "/examples/motion/positioning.scenario.yaml",
                                          kSrc + "/examples/oven/oven.scenario.yaml"};
  std::mt19937 rng(20261125);
  size_t refused = 0, ran = 0;
  for (int n = 0; n < 3000; ++n) {
    const std::string& path = files[size_t(n) % files.size()];
    const std::string text = mutate(slurp(path), rng);
    Scenario sc;
    try {
      sc = parse_scenario(text, path);
    } catch (const SourceError& e) {
      ++refused;
      ASSERT_FALSE(e.diagnostics().empty());
      for (const auto& d : e.diagnostics()) {
        ASSERT_EQ(d.where.file, path) << text;
        ASSERT_GT(d.where.line, 0) << d.to_string() << "\n" << text;
        ASSERT_FALSE(d.message.empty());
      }
      continue;
    }
    if (n % 5) continue;  // running is slower than reading: every fifth that reads well
    try {
      CellTarget cell(sc.cell, sc.program);
      bool known = true;
      for (const auto& c : sc.cases) known = known && check_case(c, cell).empty();
      if (!known || sc.cases.empty()) continue;
      CellTarget fresh(sc.cell, sc.program);
      Bounded t(fresh, 20000);
      const CaseResult r = run_case(sc.cases[0], t);
      ++ran;
      if (!r.passed) {
        EXPECT_FALSE(r.failure.empty());
      }
    } catch (const SourceError&) {
      // a mutated cell path that names another YAML: refused as the cell's own errors
    }
  }
  // The mutations must exercise both sides.
  EXPECT_GT(refused, 600u);
  EXPECT_GT(ran, 40u);
}
