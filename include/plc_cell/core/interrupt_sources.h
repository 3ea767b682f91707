#pragma once
// The interrupt sources of the FBs-PLC (manual §9.3) and their reserved labels. The labels
// belong to the IL language: the parser must refuse a jump to an interrupt routine whether
// or not a counter unit is part of the cell, so the table lives in the core and the
// interrupt controller (hsc/) builds on it.
#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell {
namespace irq {

// Source ids, in priority order for the 49 of the table.
enum Source : int {
  kHstaI = 0,
  kTimeBase0 = 1,   // 1MSI ... 100MSI = 1..8
  kHsc0I = 9,       // HSC0I/HST0I ... HSC3I/HST3I = 9..12
  kPso0I = 13,      // PSO0I ... PSO3I = 13..16 (the pulse-output axes raise them)
  kX0Up = 17,       // X0+I, X0-I, X1+I ... X15-I = 17..48
  kHsc4I = 49,      // HSC4I ... HSC7I = 49..52 (priority of their input: AMBIG-3)
  kSourceCount = 53,
};
constexpr uint32_t kTimeBaseMs[8] = {1, 2, 3, 4, 5, 10, 50, 100};

inline int x_edge_source(int x, bool falling) { return kX0Up + 2 * x + (falling ? 1 : 0); }

// Labels accepted for a source: the new name first, then the old one(s).
std::vector<std::string> source_labels(int source);
// Source of a label (new or old name, upper case); -1 if it is not reserved.
int source_of_label(const std::string& label);

}  // namespace irq
}  // namespace plc_cell
