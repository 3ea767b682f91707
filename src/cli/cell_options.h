#pragma once
// The options through which `plc_cell run`, `sim` and `check` set a cell's run and server
// settings. The server options come from Cell::server_kinds(): every setting of every
// kind is an option --<kind>-<key>, so a new server kind needs nothing here.
#include <string>
#include <vector>

#include "args.h"
#include "plc_cell/io/stop_signal.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace cli {

// The option names (without --) of every server setting, aliases included.
std::vector<std::string> server_options();
// --program, --scan, --persist, --persist-interval, --rt-priority and the server options
// given in args, each checked: a bad value is a UsageError naming the option.
CellOverrides cell_overrides(const Args& args);
// One --set ADDR=VALUE (shown as the user wrote it), written into cell before the first scan.
void apply_set(Cell& cell, const std::string& set, const std::string& shown);
// "2.500000": virtual time in s, as plc_cell sim prints it.
std::string seconds(uint64_t us);
// plc_cell sim --line (sim_line.cpp).
int sim_line(const Args& args);
// plc_cell run --line (run_line.cpp), until stop or --duration.
int run_line(const Args& args, StopSignal& stop);

}  // namespace cli
}  // namespace plc_cell
