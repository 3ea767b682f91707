#pragma once
// Planning a line's scenario in wall-clock time (docs/lines.md, "On ROS"): what
// wall_clock_target.h plans for one cell, per cell of the line. The resolution of the line is
// the worst of its cells' (a window is seen no finer than through the slowest link), the
// points read before a case and put back after are each cell's, and every refusal is said
// once at its file:line before anything is written.
#include <string>
#include <vector>

#include "plc_cell/scenario/line_wall_clock_target.h"
#include "plc_cell/scenario/resolution.h"

namespace plc_cell {
namespace scenario {

// The coarsest of rs (the largest us()); a zero Resolution when rs is empty.
Resolution worst_resolution(const std::vector<Resolution>& rs);

// The addresses cell's target polls over every case, in order, each once.
std::vector<Address> polled_in(const LineCellLink& cell, const std::vector<Case>& cases);
// The points of cell every case touches, each once, labelled CELL.LABEL.
std::vector<TouchedPoint> touched_in(const LineCellLink& cell, const std::vector<Case>& cases);

// refusals_on (wall_clock_target.h) of a line: the file's permission for target, each
// cell's mode where connected, the names no cell in reach answers and what the rules refuse.
// cases come back with their windows widened; widened says which.
std::vector<Diagnostic> refusals_on_line(const std::vector<LineCellLink>& cells, const std::string& target,
                                         const Scenario& sc, const WallClockRules& rules, std::vector<Case>* cases,
                                         std::vector<StepNote>* widened);

// "forces infeed.stop_button (X1); writes nothing", over every cell.
std::string forces_and_writes_on_line(const std::vector<LineCellLink>& cells, const std::vector<Case>& cases);

}  // namespace scenario
}  // namespace plc_cell
