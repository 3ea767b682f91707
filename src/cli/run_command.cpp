// plc_cell run: the soft PLC headless in real time until SIGINT/SIGTERM.
#include <iostream>

#include "args.h"
#include "cell_options.h"
#include "commands.h"
#include "plc_cell/core/error.h"
#include "plc_cell/io/stop_signal.h"
#include "plc_cell/online/program_watch.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace cli {

namespace {

// The cell as a real one is: no input is played by its simulation:, so each stays where the
// clients (a FATEK force, a Modbus write) leave it, as a real PLC's terminals stay where its
// wiring holds them.
// Returns the log line that says so.
std::string simulation_off(Cell& cell) {
  SimulatedCell& sim = cell.soft().simulation();
  std::string off;
  cell.plc().locked([&](ScanEngine&, Memory&) {
    for (uint32_t x : sim.simulated_inputs()) {
      sim.override_input(x);
      off += (off.empty() ? "X" : ", X") + std::to_string(x);
    }
    return 0;
  });
  return "plc_cell run: simulation off" + (off.empty() ? std::string() : ": " + off + " stay as the clients leave them");
}

}  // namespace

int cmd_run(const std::vector<std::string>& argv) {
  // Before the store, the servers and every thread: a SIGTERM at any moment from here on
  // waits until start-up is done and then stops cleanly, with the store flushed.
  StopSignal stop;
  std::vector<std::string> options = {"program", "config", "scan", "duration", "rt-priority", "persist",
                                      "persist-interval", "engine", "line", "properties"};
  const auto servers = server_options();
  options.insert(options.end(), servers.begin(), servers.end());
  Args args(argv, options, {"watch-program", "no-simulation"});
  if (!args.positional().empty()) throw UsageError("unexpected argument '" + args.positional()[0] + "'");
  if (args.has("line")) return run_line(args, stop);
  if (args.has("properties")) throw UsageError("--properties goes with --line (a line's monitor watches them)");
  const uint64_t duration = args.has("duration") ? parse_duration_us(args.get("duration")) : 0;
  Cell cell(args.get("config"), cell_overrides(args), Cell::Purpose::Serve,
            [](const std::string& l) { std::cerr << "plc_cell run: " << l << "\n"; });
  for (const auto& w : cell.soft().warnings()) std::cerr << w.to_string() << "\n";  // the PLC still runs
  const std::string no_simulation = args.has("no-simulation") ? simulation_off(cell) : "";
  if (!cell.plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program loaded");
  cell.start_servers([](const Server& s) { std::cerr << "plc_cell run: serving " << s.describe() << "\n"; });
  if (!no_simulation.empty()) std::cerr << no_simulation << "\n";  // after the servers: a first line says they are up
  std::cerr << "plc_cell run: engine " << cell.plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); })
            << "\n";
  cell.start_scanning();
  std::cerr << "plc_cell run: " << cell.program_path() << " scanning every " << cell.scan_period_us()
            << " us; Ctrl-C to stop\n";
  // A saved program goes live through the change service (docs/online-change.md).
  std::unique_ptr<online::ProgramWatch> watch;
  if (args.has("watch-program")) {
    watch = std::make_unique<online::ProgramWatch>(cell.changes(), [](const ChangeOutcome& o) {
      std::cerr << "plc_cell run: program change " << o.result << (o.why.empty() ? "" : ": " + o.why) << "\n";
      for (const auto& e : o.errors)
        std::cerr << "    line " << e.line << ":" << e.column << ": " << e.message << "\n";
      if (o.gate.configured) std::cerr << "    gate: " << o.gate.summary << "\n";
    });
    std::cerr << "plc_cell run: watching " << cell.program_path() << " for changes\n";
  }
  if (stop.wait_until_stopped(duration)) std::cerr << "plc_cell run: " << stop.signal_name() << ": stopping\n";
  watch.reset();
  const std::string priority_error = cell.loop()->priority_error();
  const auto ps = cell.persister() ? cell.persister()->status() : persist::PersistStatus();
  cell.stop();  // servers, scans, then the newest image goes to disk
  if (!priority_error.empty()) std::cerr << "plc_cell run: " << priority_error << "\n";
  if (!ps.error.empty()) std::cerr << "plc_cell run: persist error: " << ps.error << "\n";
  const auto st = cell.plc().locked([](ScanEngine& e, Memory&) { return e.stats(); });
  const std::string fault = cell.plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
  std::cerr << "plc_cell run: " << st.scans << " scans, cycle avg " << st.cycle.avg_ns() / 1000.0
            << " us max " << st.cycle.max_ns / 1000.0 << " us, wake latency max "
            << st.wake_latency.max_ns / 1000.0 << " us, overruns " << st.overruns << " ("
            << st.overruns_off_cpu << " with the scan thread off the CPU)\n";
  if (!fault.empty()) std::cerr << "fault: " << fault << "\n";
  return fault.empty() ? 0 : 1;
}

Command run_command() {
  return {"run",
          "--program FILE [--config FILE] [--scan 1ms] [--duration T] [--rt-priority N]\n"
          "         [--persist FILE] [--persist-interval DURATION] [--engine E] [--watch-program]\n"
          "         [--no-simulation]\n"
          "         [--SERVER-SETTING VALUE ...]\n"
          "         run the soft PLC in real time until interrupted; keep the retentive ranges in\n"
          "         FILE across restarts and crashes (default 100ms); serve the cell's protocols\n"
          "         (below), each option overriding the cell YAML's servers.SERVER.SETTING;\n"
          "         --watch-program: a saved program goes live in RUN, gated (docs/online-change.md)\n"
          "         --no-simulation: the cell's simulation plays no input (as on a real cell)\n"
          "     run --line LINE.yaml [--duration T] [--engine E] [--http-tcp HOST:PORT] [--http-...]\n"
          "         [--properties FILE.scenario.yaml]\n"
          "         a line of cells in real time (docs/lines.md), with one monitor for all of them;\n"
          "         --properties: the file's properties watched at every scan (docs/monitor.md)\n",
          cmd_run};
}

}  // namespace cli
}  // namespace plc_cell
