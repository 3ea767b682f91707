#pragma once
// What a program change in RUN keeps and what it may not do (docs/online-change.md). The
// FBs manual gives no rules for editing in RUN; these are what the engine can carry over a
// swap at a scan boundary.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/program.h"

namespace plc_cell {

class ScanEngine;

// Per edge slot of next, the slot of running it takes its edge memory from (~0u: starts at
// 0). An edge instruction is the same one in both programs when its kind, its device and
// its place among the instructions of that kind and device agree: a TU contact on T51 keeps
// what it saw last scan, so a change elsewhere cannot make it fire.
std::vector<uint32_t> carried_edges(const Program& running, const Program& next);

// Why next may not replace the engine's program in RUN, one line each ("" none): a timer
// that is timing needs its TMR in the new program, or its contact would freeze mid-count.
// Empty in STOP. Call with the PLC lock held, right before load_online.
std::vector<std::string> online_change_refusals(const ScanEngine& engine, const Program& next);

}  // namespace plc_cell
