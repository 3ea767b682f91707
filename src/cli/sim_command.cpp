// plc_cell sim: deterministic virtual-time runs for testing ladder programs in CI.
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include "args.h"
#include "cell_options.h"
#include "commands.h"
#include "record_option.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {
namespace cli {


namespace {

// The --watch list: each name as given (format suffix and all), its address and format.
struct Watches {
  std::vector<std::string> names;
  std::vector<Address> addrs;
  std::vector<ValueFormat> formats;
};

Watches watches(const Args& args, Cell& cell, VirtualRun& run) {
  Watches out;
  for (const auto& w : args.all("watch"))
    for (const auto& n : split_list(w)) {
      std::pair<std::string, ValueFormat> nf;
      Address a;
      try {
        nf = split_format(n);
        a = cell.config().resolve(nf.first);
        check_format(a, nf.second, n);
      } catch (const Error& e) {
        throw Error("--watch " + std::string(e.what()));
      }
      out.names.push_back(n);
      out.addrs.push_back(a);
      out.formats.push_back(nf.second);
      run.watch(a);
    }
  return out;
}

}  // namespace

int cmd_sim(const std::vector<std::string>& argv) {
  Args args(argv, {"program", "config", "duration", "scan", "set", "watch", "trace", "engine", "record", "rtc-start",
                   "line"});
  if (!args.positional().empty()) throw UsageError("unexpected argument '" + args.positional()[0] + "'");
  if (args.has("line")) return sim_line(args);
  const uint64_t duration = parse_duration_us(args.require("duration"));
  Cell cell(args.get("config"), cell_overrides(args), Cell::Purpose::Simulate);
  const uint64_t scan = cell.scan_period_us();
  for (const auto& w : cell.soft().warnings()) std::cerr << w.to_string() << "\n";  // the run goes on

  Plc& plc = cell.plc();
  if (!plc.set_mode(RunMode::Run)) throw Error("cannot RUN: no program loaded");
  // After RUN's clearing of the non-retentive memory: the values hold at the first scan,
  // retentive or not.
  for (const auto& s : args.all("set")) apply_set(cell, s, s);
  // Said only on a fallback: the status line carries the generation time, and sim's output
  // is the same on every run.
  const std::string fallback =
      plc.locked([](ScanEngine& e, Memory&) { return e.engine_fell_back() ? e.engine_status() : std::string(); });
  if (!fallback.empty()) std::cerr << "plc_cell sim: engine " << fallback << "\n";

  VirtualRun run(plc, scan);
  Watches w = watches(args, cell, run);
  std::ofstream trace;
  if (args.has("trace")) {
    trace.open(args.get("trace"));
    if (!trace) throw Error("cannot write the trace file " + args.get("trace"));
    trace << "time_s,address,value,event,source\n";
    run.trace_events();
  }
  const auto on_change = [&](const WatchChange& c) {
    if (trace.is_open())
      trace << seconds(c.t_us) << "," << w.names[c.watch] << ","
            << format_value(w.addrs[c.watch], c.value, w.formats[c.watch]) << "\n";  // scan rows: 3 fields
  };
  const auto on_event = [&](const SimEvent& e) {
    // Events carry their instant to the ns (scan rows are on the scan's us).
    trace << e.t_ns / 1000000000 << "." << std::setw(9) << std::setfill('0') << e.t_ns % 1000000000
          << std::setfill(' ') << ",,," << e.kind << "," << e.source << "\n";
  };
  if (args.has("record")) {
    recording::Recorder rec(recording_info(cell, "plc_cell sim"));
    rec.start(plc);
    const uint64_t end = run.now_us() + duration;
    while (run.now_us() < end) {
      const uint64_t t = run.now_us();
      run.run_for(scan, on_change, on_event);  // one scan
      rec.scanned(plc, t);
    }
    rec.save(args.get("record"));
  } else {
    run.run_for(duration, on_change, on_event);
  }

  const bool running = plc.mode() == RunMode::Run;
  std::cout << "# plc_cell sim: " << run.scans() << " scans of " << scan << " us, virtual time "
            << seconds(run.now_us()) << " s, " << (running ? "RUN" : "STOP") << "\n";
  const std::string fault = plc.locked([](ScanEngine& e, Memory&) { return e.fault(); });
  if (!fault.empty()) std::cout << "# fault: " << fault << "\n";
  const auto values = run.values();
  for (size_t i = 0; i < w.names.size(); ++i)
    std::cout << w.names[i] << " = " << format_value(w.addrs[i], values[i], w.formats[i]) << "\n";
  return fault.empty() ? 0 : 1;
}

Command sim_command() {
  return {"sim",
          "--program FILE [--config FILE] --duration 2.5s [--scan 1ms] [--engine E]\n"
          "         [--set ADDR=VALUE ...] [--watch ADDR,...] [--trace FILE.csv]\n"
          "         [--record FILE.plcrec] [--rtc-start 2024-01-01T00:00:00|host]\n"
          "         run the program in virtual time and print the watched values;\n"
          "         --record: every change of memory with its instant (docs/recordings.md)\n"
          "     sim --line LINE.yaml --duration 10s [--engine E] [--set CELL.ADDR=VALUE ...]\n"
          "         [--watch CELL.NAME,...] [--trace FILE.csv] [--record FILE.plcrec]\n"
          "         a line of cells on one virtual clock (docs/lines.md)\n",
          cmd_sim};
}

}  // namespace cli
}  // namespace plc_cell
