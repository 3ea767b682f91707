#pragma once
// The cells one monitor serves from the command line (docs/monitor.md, "One monitor for a
// line"): a line's cells in this process (`plc_cell run --line`) or a line's recording
// (`plc_cell monitor --recording`), each cell a named source, with the line's wires; and
// the --http-* settings both commands take.
#include <string>

#include "args.h"
#include "plc_cell/line/line.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/source_set.h"
#include "plc_cell/recording/line_recording.h"

namespace plc_cell {
namespace cli {

// Each cell of l built here as a LiveSource named as in the line file, and the line's wires.
monitor::SourceSet line_cells(line::Line& l);
// Each cell of a line's recording as a ReplaySource, and its wires.
monitor::SourceSet recorded_cells(const recording::LineReader& line, const std::string& path);
// The http kind's settings from --http-*; default_endpoint when --http-tcp is not given.
monitor::HttpSettings http_options(const Args& args, const std::string& default_endpoint);

}  // namespace cli
}  // namespace plc_cell
