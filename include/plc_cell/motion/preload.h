#pragma once
// The cell YAML's tables and parameter tables (axes: psoN.table, psoN.params with at:,
// gpN.table), written into the registers at each STOP -> RUN as an MMI would.
#include "plc_cell/motion/axis_config.h"

namespace plc_cell {

class Memory;

namespace motion {

void preload_tables(Memory& mem, const AxesConfig& cfg);

}  // namespace motion
}  // namespace plc_cell
