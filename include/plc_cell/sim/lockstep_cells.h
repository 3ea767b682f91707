#pragma once
// The lockstep engine on a whole cell (docs/native-engine.md, "Lockstep"): a twin, a second
// SoftCell built from the same files (every extension: counters, axes, modules, RTC,
// simulation), runs the program on the interpreter beside the cell on the native engine,
// scan for scan, with the same inputs: before each scan the twin takes the cell's memory
// (what clients and the front end wrote), its input terminals, its RUN/STOP, an online
// change, and what the cell's simulation stopped or resumed playing; the core compares the
// two after every run of the program and every scan (core/native/lockstep.h).
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

// From now on cell runs in lockstep with twin, which must outlive cell's engine (the Cell of
// runtime/cell.h owns both). What drives an extension directly rather than through memory
// or the inputs (a scenario's probe stimulus) must drive the twin's too.
void run_in_lockstep(SoftCell& cell, SoftCell& twin);

}  // namespace plc_cell
