#include "monitor_cells.h"

#include "cell_options.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/monitor/live_source.h"
#include "plc_cell/monitor/server_kind.h"
#include "plc_cell/recording/replay_source.h"
#include "plc_cell/sim/soft_cell.h"
#include "record_option.h"

namespace plc_cell {
namespace cli {

namespace {

// "infeed.release -> robot.nest_sensor (delay 20 ms)" -> its two ends and the whole text.
monitor::SetWire parse_wire_text(const std::string& text) {
  monitor::SetWire w;
  w.text = text;
  const size_t arrow = text.find(" -> ");
  if (arrow == std::string::npos) return w;  // no ends: the overview says it cannot read them
  w.from = text.substr(0, arrow);
  const std::string rest = text.substr(arrow + 4);
  w.to = rest.substr(0, rest.find(" ("));
  return w;
}

}  // namespace

monitor::SourceSet line_cells(line::Line& l) {
  monitor::SourceSet set;
  set.set_title("line " + l.name());
  for (size_t i = 0; i < l.size(); ++i) {
    Cell* c = l.cell(i);
    if (!c) continue;  // elsewhere: not this process's to show
    ServerContext context(c->plc());
    context.config = &c->config();
    context.extensions = &c->soft().extensions();
    context.program_path = c->program_path();
    context.changes = &c->changes();
    set.add(l.entry(i).name, std::make_unique<monitor::LiveSource>(context, "cell " + l.entry(i).name));
  }
  for (const auto& w : l.wires()) set.add_wire({w.entry.from, w.entry.to, wire_text(w.entry)});
  return set;
}

monitor::SourceSet recorded_cells(const recording::LineReader& line, const std::string& path) {
  monitor::SourceSet set;
  set.set_title("line " + line.info().line + " (recording " + path + ")");
  for (size_t i = 0; i < line.size(); ++i)
    set.add(line.name(i), std::make_unique<recording::ReplaySource>(line.cell(i), path + " (cell " + line.name(i) + ")",
                                                                    SoftCell::functions()));
  for (const auto& w : line.info().wires) set.add_wire(parse_wire_text(w));
  return set;
}

monitor::HttpSettings http_options(const Args& args, const std::string& default_endpoint) {
  std::vector<SettingOverride> overrides = cell_overrides(args).servers;
  if (!args.has("http-tcp")) overrides.push_back({"http", "tcp", {default_endpoint}, "the default"});
  const ServerKind kind = monitor::server_kind();
  const auto merged = merge_server_settings({kind}, CellConfig{}, overrides);
  return monitor::http_settings(merged.at("http"));
}

}  // namespace cli
}  // namespace plc_cell
