// plc_cell run: the soft PLC headless in real time until SIGINT/SIGTERM.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <thread>

#include "args.h"
#include "commands.h"
#include "plc_cell/comm/protocol_functions.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/config/server_settings.h"
#include "plc_cell/io/server.h"
#include "plc_cell/io/stop_signal.h"
#include "plc_cell/persist/persister.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace cli {

int cmd_run(const std::vector<std::string>& argv) {
  // Before the store, the servers and every thread: a SIGTERM at any moment from here on
  // waits until start-up is done and then stops cleanly, with the store flushed.
  StopSignal stop;
  std::vector<std::string> options = {"program", "config", "scan", "duration", "rt-priority"};
  // @run-options: subsystems append their option names (e.g. "fatek-tcp") here
  options.insert(options.end(), {"fatek-tcp", "fatek-serial", "station"});
  options.insert(options.end(), {"persist", "persist-interval"});
  options.insert(options.end(), {"fatek-writable", "fatek-max-connections", "fatek-idle-timeout"});
  options.insert(options.end(), {"modbus-writable", "modbus-max-connections", "modbus-idle-timeout"});
  options.insert(options.end(), {"modbus-tcp", "modbus-rtu", "modbus-id", "modbus-gateway", "modbus-gateway-wait", "modbus-gateway-retries"});
  Args args(argv, options);
  SoftCell cell(args.get("config"), args.get("program"), install_protocol_functions);
  const uint64_t scan = args.has("scan") ? parse_duration_us(args.get("scan")) : cell.config().scan_period_us;
  if (scan == 0) throw UsageError("--scan must be positive");
  const uint64_t duration = args.has("duration") ? parse_duration_us(args.get("duration")) : 0;
  // Retentive memory from the last run, before the first scan and the first request.
  PersistSettings keep = cell.config().persist;
  if (args.has("persist")) keep.file = args.get("persist");
  if (args.has("persist-interval")) keep.interval_us = parse_duration_us(args.get("persist-interval"));
  std::unique_ptr<persist::Persister> persister;
  if (!keep.file.empty())
    persister = std::make_unique<persist::Persister>(cell.plc(), keep,
                                                      [](const std::string& l) { std::cerr << "plc_cell run: " << l << "\n"; });
  if (!cell.plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program loaded");

  std::vector<std::unique_ptr<Server>> servers;
  // @run-servers: subsystems create their servers from args here (servers.push_back(...))
  const ServerSettings& from_yaml = cell.servers();  // read (and checked) with the cell
  add_fatek_servers(args, from_yaml, cell.plc(), &servers);
  add_modbus_servers(args, from_yaml, cell.plc(), &servers);
  for (auto& s : servers) {
    s->start();
    std::cerr << "plc_cell run: serving " << s->describe() << "\n";
  }

  RealTimeLoop loop(cell.plc(), std::chrono::microseconds(scan));
  loop.set_priority(static_cast<int>(args.get_int("rt-priority", 0, 0, 99)));
  loop.start();
  std::cerr << "plc_cell run: " << cell.program_path() << " scanning every " << scan
            << " us; Ctrl-C to stop\n";
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    std::chrono::milliseconds wait(1000);
    if (duration) {
      const auto left = std::chrono::microseconds(duration) - (std::chrono::steady_clock::now() - t0);
      if (left <= left.zero()) break;
      wait = std::min(wait, std::chrono::duration_cast<std::chrono::milliseconds>(left) + std::chrono::milliseconds(1));
    }
    if (stop.wait_for(wait)) {
      std::cerr << "plc_cell run: " << stop.signal_name() << ": stopping\n";
      break;
    }
  }
  loop.stop();
  if (!loop.priority_error().empty()) std::cerr << "plc_cell run: " << loop.priority_error() << "\n";
  for (auto& s : servers) s->stop();
  servers.clear();
  if (persister) {
    const auto ps = persister->status();
    if (!ps.error.empty()) std::cerr << "plc_cell run: persist error: " << ps.error << "\n";
    persister.reset();  // the newest image goes to disk
  }
  const auto st = cell.plc().locked([](ScanEngine& e, Memory&) { return e.stats(); });
  const std::string fault = cell.plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
  std::cerr << "plc_cell run: " << st.scans << " scans, cycle avg " << st.cycle.avg_ns() / 1000.0
            << " us max " << st.cycle.max_ns / 1000.0 << " us, wake latency max "
            << st.wake_latency.max_ns / 1000.0 << " us, overruns " << st.overruns << "\n";
  if (!fault.empty()) std::cerr << "fault: " << fault << "\n";
  return fault.empty() ? 0 : 1;
}

}  // namespace cli
}  // namespace plc_cell
