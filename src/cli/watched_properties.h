#pragma once
// --properties FILE.scenario.yaml of the monitor of a line (docs/monitor.md, "Properties"):
// the file's properties, checked against the line it watches, and their watcher over the
// line running here (`plc_cell run --line`) or over a line's recording (`plc_cell monitor
// --recording`), which the overview shows.
#include <memory>
#include <string>

#include "plc_cell/line/line.h"
#include "plc_cell/monitor/source_set.h"
#include "plc_cell/recording/line_recording.h"
#include "plc_cell/scenario/property_watcher.h"

namespace plc_cell {
namespace cli {

// The properties of the line in scenario file `path`, watched after each scan of l's cells
// (set: l's cells as the monitor serves them). The file's line: must be l's file.
std::shared_ptr<scenario::PropertyWatcher> watch_line(const std::string& path, line::Line& l,
                                                      const monitor::SourceSet& set);
// The same over every recorded instant of a line's recording, evaluated here; the file's
// line: must be a line of the recording's name.
std::shared_ptr<scenario::PropertyWatcher> watch_recording(const std::string& path, const recording::LineReader& r,
                                                           const monitor::SourceSet& set);
// One line per property, each after prefix: how often it was violated and when last.
std::string property_summary(const monitor::PropertyReport& r, const std::string& prefix);

}  // namespace cli
}  // namespace plc_cell
