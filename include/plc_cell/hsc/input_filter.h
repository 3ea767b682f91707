#pragma once
// The digital input filter of X0-X35 (manual §9.7): six groups, each with one
// setting. Every setting is reduced to one number, the minimum width of an ON or
// OFF pulse that passes: a time-domain setting is that width itself; a frequency
// cut-off f lets through square waves up to f, i.e. half-periods >= 1/(2f).
// docs/counters-and-interrupts.md ("Digital input filter") gives the choices.
#include <array>
#include <cstdint>
#include <string>

namespace plc_cell {
namespace hsc {

constexpr int kFilteredInputs = 36;  // X0-X35

struct FilterGroup {
  const char* name;  // as written in the YAML: "X0-X3"
  int first, last;
  bool frequency;    // the frequency domain is allowed (X0-X15 only)
  bool tenths;       // 1-15 x 0.1 ms is allowed (X0-X15 only)
};
const std::array<FilterGroup, 6>& filter_groups();

// The 8 frequency selections (AMBIG-4: the manual names 14 kHz, 28 kHz and 1.8 MHz
// only): 1.8 MHz / 2^k, k = 7..0, with their names.
struct FilterFrequency {
  const char* name;  // "28kHz"
  double hz;         // 28125
};
const std::array<FilterFrequency, 8>& filter_frequencies();

// Minimum pulse width that a cut-off frequency lets through, in ns (rounded).
uint64_t frequency_filter_ns(double hz);

}  // namespace hsc
}  // namespace plc_cell
