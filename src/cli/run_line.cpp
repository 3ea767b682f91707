// plc_cell run --line: a line's cells in real time, each on its own scan thread, the wires
// carried between them, and one monitor for all of them (docs/lines.md, "One monitor").
#include <iostream>

#include "cell_options.h"
#include "monitor_cells.h"
#include "plc_cell/core/error.h"
#include "plc_cell/line/line.h"
#include "watched_properties.h"

namespace plc_cell {
namespace cli {

int run_line(const Args& args, StopSignal& stop) {
  for (const char* o : {"config", "program", "scan", "persist", "persist-interval", "rt-priority", "watch-program",
                        "no-simulation"})
    if (args.has(o)) throw UsageError(std::string("--") + o + " goes with a cell, not --line: a line file names its cells'");
  for (const auto& s : cell_overrides(args).servers)
    if (s.kind != "http")
      throw UsageError("--" + s.kind + "-...: a line's cells serve no protocols from the command line; --http-* "
                       "serves the line's monitor");
  const uint64_t duration = args.has("duration") ? parse_duration_us(args.get("duration")) : 0;
  line::LineOptions o;
  if (args.has("engine")) o.run.push_back({"", "engine", {args.get("engine")}, "--engine"});
  o.log = [](const std::string& l) { std::cerr << "plc_cell run: " << l << "\n"; };
  line::Line l(args.get("line"), o);
  for (size_t i = 0; i < l.size(); ++i)
    for (const auto& w : l.cell(i)->soft().warnings()) std::cerr << w.to_string() << "\n";  // the line still runs
  monitor::SourceSet cells = line_cells(l);
  std::shared_ptr<scenario::PropertyWatcher> watched;
  if (args.has("properties")) {
    watched = watch_line(args.get("properties"), l, cells);
    cells.watch(watched);
  }
  std::unique_ptr<monitor::HttpServer> server;
  if (args.has("http-tcp")) server = std::make_unique<monitor::HttpServer>(std::move(cells), http_options(args, ""));
  l.start_real_time();
  if (server) {
    server->start();
    std::cerr << "plc_cell run: serving " << server->describe() << " for line " << l.name() << " (" << l.names()
              << ")\n";
  }
  std::cerr << "plc_cell run: line " << l.name() << ": " << l.names() << " scanning; Ctrl-C to stop" << std::endl;
  if (stop.wait_until_stopped(duration)) std::cerr << "plc_cell run: " << stop.signal_name() << ": stopping\n";
  if (server) server->stop();  // no page reads a cell that is stopping
  l.stop();
  if (watched) {
    watched->flush();
    std::cerr << property_summary(watched->report(), "plc_cell run: ");
  }
  const std::string fault = l.fault();
  if (!fault.empty()) std::cerr << "fault: " << fault << "\n";
  return fault.empty() ? 0 : 1;
}

}  // namespace cli
}  // namespace plc_cell
