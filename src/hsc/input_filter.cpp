#include "plc_cell/hsc/input_filter.h"

#include <cmath>

namespace plc_cell {
namespace hsc {

const std::array<FilterGroup, 6>& filter_groups() {
  static const std::array<FilterGroup, 6> g = {{{"X0-X3", 0, 3, true, true},
                                                {"X4-X7", 4, 7, true, true},
                                                {"X8-X11", 8, 11, true, true},
                                                {"X12-X15", 12, 15, true, true},
                                                {"X16-X23", 16, 23, false, false},
                                                {"X24-X35", 24, 35, false, false}}};
  return g;
}

const std::array<FilterFrequency, 8>& filter_frequencies() {
  static const std::array<FilterFrequency, 8> f = {{{"14kHz", 14062.5},
                                                    {"28kHz", 28125},
                                                    {"56kHz", 56250},
                                                    {"112kHz", 112500},
                                                    {"225kHz", 225000},
                                                    {"450kHz", 450000},
                                                    {"900kHz", 900000},
                                                    {"1.8MHz", 1800000}}};
  return f;
}

uint64_t frequency_filter_ns(double hz) { return static_cast<uint64_t>(std::llround(1e9 / (2 * hz))); }

}  // namespace hsc
}  // namespace plc_cell
