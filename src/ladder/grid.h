#pragma once
// Internal: a Rung (rung.h) placed on the grid of its Network, with its power nodes.
#include "elements.h"
#include "rung.h"

namespace plc_cell {
namespace ladder {

// Fills rows, cols, elements, wires and nodes of `net` from a drawable rung.
void draw_rung(const Rung& rung, const Drawer& drawer, Network* net);

// A network of one flow instruction (LBL, RTS, RTI, FOR, NEXT, END): its box alone.
void draw_flow(uint32_t instruction, const Drawer& drawer, Network* net);

}  // namespace ladder
}  // namespace plc_cell
