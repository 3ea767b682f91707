// plc_cell monitor: the browser monitor on a recorded run (docs/recordings.md) or on a real
// FATEK or TRi PLC polled through its host link (docs/monitor-remote.md), with the same
// --http-* options as `plc_cell run`.
#include <iostream>
#include <memory>

#include "args.h"
#include "cell_options.h"
#include "commands.h"
#include "monitor_cells.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/stop_signal.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/server_kind.h"
#include "plc_cell/recording/line_recording.h"
#include "plc_cell/recording/replay_source.h"
#include "plc_cell/remote/fatek_link.h"
#include "plc_cell/remote/remote_source.h"
#include "plc_cell/remote/tri_link.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/soft_cell.h"
#include "watched_properties.h"

namespace plc_cell {
namespace cli {

namespace {

constexpr const char* kDefaultEndpoint = "127.0.0.1:8080";

// The recording, or with --cell that cell of a line's recording (recording/line_recording.h).
recording::Reader load_recording(const Args& args) {
  const std::string path = args.get("recording");
  if (!args.has("cell")) return recording::Reader::load(path);
  const recording::LineReader line = recording::LineReader::load(path);
  if (const recording::Reader* r = line.find(args.get("cell"))) return *r;
  std::string cells;
  for (size_t i = 0; i < line.size(); ++i) cells += (i ? ", " : "") + line.name(i);
  throw UsageError("--cell " + args.get("cell") + ": line " + line.info().line + " has no such cell (" + cells + ")");
}

// --open-at: the cursor of src (and, through the server, of the cells it is shown with).
void open_at(const Args& args, recording::ReplaySource& src) {
  if (!args.has("open-at")) return;
  const std::string at = args.get("open-at");
  if (at == "failure") {
    if (!src.failure_us())
      throw Error(args.get("recording") + " has no failure: its case passed, or it is not a test case's");
    src.seek(*src.failure_us());
    return;
  }
  uint64_t t;
  try {
    t = parse_duration_us(at);
  } catch (const Error& e) {
    throw UsageError("--open-at " + at + ": failure or a time such as 2.5s (" + e.what() + ")");
  }
  src.seek(t);
}

std::unique_ptr<monitor::Source> replay_source(const Args& args) {
  const std::string path = args.get("recording");
  const std::string name = args.has("cell") ? path + " (cell " + args.get("cell") + ")" : path;
  auto src = std::make_unique<recording::ReplaySource>(load_recording(args), name, SoftCell::functions());
  open_at(args, *src);
  return src;
}

// A line's recording without --cell: every cell, one cursor (docs/monitor.md).
bool is_line_recording(const Args& args) {
  return args.has("recording") && !args.has("cell") &&
         recording::format_version(recording::read_recording_file(args.get("recording"))) == recording::kLineFormatVersion;
}

monitor::SourceSet line_replay(const Args& args) {
  const std::string path = args.get("recording");
  const recording::LineReader line = recording::LineReader::load(path);
  monitor::SourceSet set = recorded_cells(line, path);
  // Every cell's cursor at the instant asked for: the line's failure is one instant of all.
  for (size_t i = 0; i < set.size(); ++i) open_at(args, static_cast<recording::ReplaySource&>(set.source(i)));
  if (args.has("properties")) set.watch(watch_recording(args.get("properties"), line, set));
  return set;
}

// The user's IL copy: --program, or the program and signals of the cell --config names.
std::shared_ptr<const monitor::ProgramView> program_view(const Args& args) {
  if (!args.has("config")) return remote::load_program_view(args.require("program"), SoftCell::functions());
  CellOverrides o;
  o.program = args.get("program");
  Cell cell(args.get("config"), o, Cell::Purpose::Check);
  return remote::load_program_view(cell.program_path(), SoftCell::functions(), cell.config().signals);
}

std::unique_ptr<monitor::Source> remote_source(const Args& args) {
  const int timeout_ms = int(parse_duration_us(args.get("timeout", "1s")) / 1000);
  if (timeout_ms < 10 || timeout_ms > 60000) throw UsageError("--timeout: between 10ms and 60s");
  std::unique_ptr<remote::Link> link;
  const std::string option = args.has("fatek") ? "fatek" : "tri";
  try {
    if (option == "fatek") {
      remote::FatekLinkOptions o;
      o.endpoint = args.get("fatek");
      o.station = int(args.get_int("station", 1, 1, 254));
      o.timeout_ms = timeout_ms;
      link = std::make_unique<remote::FatekLink>(o);
    } else {
      remote::TriLinkOptions o;
      o.endpoint = args.get("tri");
      o.id = int(args.get_int("id", 1, 0, 255));
      o.timeout_ms = timeout_ms;
      link = std::make_unique<remote::TriLink>(o);
    }
  } catch (const Error& e) {
    throw UsageError("--" + option + ": " + e.what());  // the endpoint's text, refused
  }
  return std::make_unique<remote::RemoteSource>(std::move(link), program_view(args));
}

std::vector<std::string> options() {
  std::vector<std::string> out = {"recording", "cell", "open-at", "fatek", "tri", "program", "config",
                                  "station", "id", "timeout", "duration", "properties"};
  const ServerKind kind = monitor::server_kind();
  for (const auto& s : kind.settings) out.push_back(kind.option(s).substr(2));
  return out;
}

}  // namespace

int cmd_monitor(const std::vector<std::string>& argv) {
  StopSignal stop;
  Args args(argv, options());
  if (!args.positional().empty()) throw UsageError("unexpected argument '" + args.positional()[0] + "'");
  const int given = int(args.has("recording")) + int(args.has("fatek")) + int(args.has("tri"));
  if (given != 1) throw UsageError("give one of --recording FILE, --fatek HOST:PORT|DEV, --tri HOST:PORT|DEV");
  if (args.has("open-at") && !args.has("recording")) throw UsageError("--open-at goes with --recording");
  if (args.has("cell") && !args.has("recording")) throw UsageError("--cell goes with --recording (a line's)");
  const uint64_t duration = args.has("duration") ? parse_duration_us(args.get("duration")) : 0;
  const monitor::HttpSettings settings = http_options(args, kDefaultEndpoint);
  if (args.has("properties") && !is_line_recording(args))
    throw UsageError("--properties goes with a line's recording, all its cells (no --cell): its overview shows them");
  std::unique_ptr<monitor::Source> source;
  std::unique_ptr<monitor::HttpServer> served;
  std::string what;
  if (is_line_recording(args)) {
    monitor::SourceSet cells = line_replay(args);
    what = cells.title() + ": cells " + cells.names();
    served = std::make_unique<monitor::HttpServer>(std::move(cells), settings);
  } else {
    source = args.has("recording") ? replay_source(args) : remote_source(args);
    what = source->describe();
    served = std::make_unique<monitor::HttpServer>(*source, settings);
  }
  monitor::HttpServer& server = *served;
  server.start();
  std::cerr << "plc_cell monitor: serving " << server.describe() << " for " << what << "; Ctrl-C to stop" << std::endl;
  stop.wait_until_stopped(duration);
  server.stop();
  return 0;
}

Command monitor_command() {
  return {"monitor",
          "--recording FILE [--cell NAME] [--open-at failure|T] [--http-tcp HOST:PORT] [--http-...]\n"
          "         [--properties FILE.scenario.yaml] (a line's recording: its properties at the cursor)\n"
          "         --fatek HOST:PORT|DEV [--station N] (--program FILE.il | --config CELL.yaml)\n"
          "         --tri HOST:PORT|DEV [--id N] (--program FILE.il | --config CELL.yaml)\n"
          "         [--timeout 1s] [--duration T]\n"
          "         the browser monitor on a recorded run (docs/recordings.md; a line's recording:\n"
          "         every cell, or with --cell one of them) or on a real PLC\n"
          "         through its host link (docs/monitor-remote.md); 127.0.0.1:8080 by default\n",
          cmd_monitor};
}

}  // namespace cli
}  // namespace plc_cell
