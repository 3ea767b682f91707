#pragma once
// The cell YAML's scan settings and simulated inputs put into effect. The config layer
// only reads and checks; the signal classes it names live here, above it.
#include "plc_cell/config/cell_config.h"

namespace plc_cell {

class Plc;
class SimulatedCell;

// Applies scan settings and retentive ranges to the engine and installs the input
// signals in sim. Does not load the program.
void apply_cell_config(const CellConfig& cfg, Plc& plc, SimulatedCell& sim);

}  // namespace plc_cell
