#pragma once
// A generated cell while its parts write it (cell_part.h): the fuzzer's bytes, the inputs
// the parts share, the YAML sections and the IL each part adds to. cell_generator.cpp
// runs the registered parts in their order and assembles the cell from the draft.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <set>
#include <sstream>
#include <string>
#include <list>
#include <utility>
#include <vector>

#include "cell_generator.h"

namespace plc_cell_fuzz {

using Fdp = FuzzedDataProvider;

template <class T, size_t N>
const T& pick(Fdp& f, const T (&a)[N]) {
  return a[f.ConsumeIntegralInRange<size_t>(0, N - 1)];
}
inline bool chance(Fdp& f, int one_in) { return f.ConsumeIntegralInRange<int>(1, one_in) == 1; }
std::string hex(uint32_t v);
std::string indent(const std::string& text, int n);
// A time in seconds between 0 and 3, as a YAML number.
std::string seconds(Fdp& f);

// X0-X47 as the parts hand them out. X0-X15 are the high-speed inputs (counters,
// interrupts, DOG, PG0, wiring); a pin is taken once so that most cells are accepted.
// Rarely a taken pin is handed out again: the builder must then refuse the cell with a
// message.
struct Pins {
  bool used[48] = {};
  int take(Fdp& f, int lo, int hi);
  bool claim(int x);
};

struct CellDraft {
  explicit CellDraft(Fdp& fdp) : f(fdp) {}
  Fdp& f;
  Pins pins;
  // What one part reserves for another to respect ("HHSC0": a wired axis counts on it).
  std::set<std::string> claims;
  // The interrupt routines the program must have (LBL ... RTI after END).
  std::vector<std::string> labels;
  std::ostringstream init;  // after ORG M1924 (first scan)
  std::ostringstream body;  // the main program
  std::ostringstream sim;   // simulation: inputs: entries
  GeneratedCell out;

  // A top-level YAML section's text (indented by the part), in the order first asked for;
  // a reference stays valid while the draft lives.
  std::ostringstream& section(const std::string& name);
  const std::list<std::pair<std::string, std::ostringstream>>& sections() const { return sections_; }

 private:
  std::list<std::pair<std::string, std::ostringstream>> sections_;
};

}  // namespace plc_cell_fuzz
