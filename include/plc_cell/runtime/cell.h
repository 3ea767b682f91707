#pragma once
// The composition root. A Cell is built from the cell YAML (and program) plus what a
// front end overrides (`plc_cell run` options, plc_node parameters), and owns everything
// the cell is made of: the soft PLC with its subsystems (SoftCell), its protocol servers,
// its retentive store and its real-time scan driver. plc_node, `plc_cell run`, `sim` and
// `check`, the fuzzers and the benchmarks all build one, so what one refuses every one
// refuses with the same message; `check` is "build, then stop".
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "plc_cell/config/server_kind.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/io/server.h"
#include "plc_cell/online/change_service.h"
#include "plc_cell/persist/persister.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

// What a front end sets on top of the YAML. Every value is text with its origin
// ("--scan", "~scan_period") so that an error names where the value came from.
struct CellOverrides {
  std::string program;  // overrides cell.program
  // Run settings, keys of Cell::run_settings(): scan_period, rt_priority, persist_file,
  // persist_interval, engine, rtc_start (kind is ignored).
  std::vector<SettingOverride> run;
  // A served cell scanned in virtual time (plc_node ~virtual_time). Every other purpose
  // than Serve is virtual time anyway.
  bool virtual_time = false;
  // Server settings, keys of Cell::server_kinds(): {"modbus", "id", {"7"}, "--modbus-id"}.
  std::vector<SettingOverride> servers;
};

class Cell {
 public:
  enum class Purpose {
    Check,     // build and stop: FUN150/151 open no port, no store is opened
    Simulate,  // virtual time (plc_cell sim): FUN150/151 ports open, no servers start
    Serve,     // real time (plc_cell run, plc_node): the store restores memory
  };

  // Throws SourceError listing every error of the YAML and program, or Error naming the
  // override at fault. Builds the servers but starts nothing. log gets the store's events.
  Cell(const std::string& config_path, const CellOverrides& overrides, Purpose purpose,
       std::function<void(const std::string&)> log = {});
  ~Cell();
  Cell(const Cell&) = delete;
  Cell& operator=(const Cell&) = delete;

  // Every protocol server kind a cell can offer; a new kind registers here
  // (src/runtime/server_kinds.cpp) and every front end offers its settings.
  static const std::vector<ServerKind>& server_kinds();
  // The run settings' schema: what `plc_cell run` and plc_node set besides the servers.
  static const std::vector<SettingSpec>& run_settings();
  // The sections a cell's extensions claim (with the core's, the keys of a cell file).
  static std::set<std::string> sections();

  SoftCell& soft() { return *soft_; }
  // In lockstep (plc.engine, --engine): the interpreter's twin of the whole cell
  // (sim/lockstep_cells.h), which scans with the cell; else nullptr. What drives an
  // extension directly (a scenario's stimulus) drives the twin's too.
  SoftCell* twin() { return twin_.get(); }
  Plc& plc() { return soft_->plc(); }
  const CellConfig& config() const { return soft_->config(); }
  const std::string& program_path() const { return soft_->program_path(); }
  // Changes of the running program (docs/online-change.md): the one path plc_node's
  // ~load_program, the monitor and `plc_cell run --watch-program` take.
  online::ChangeService& changes() { return *changes_; }
  uint64_t scan_period_us() const { return scan_us_; }
  int rt_priority() const { return rt_priority_; }
  const PersistSettings& persist_settings() const { return persist_; }
  // nullptr unless Serve with a persist file.
  persist::Persister* persister() { return persister_.get(); }
  const std::map<std::string, Settings>& server_settings() const { return server_settings_; }
  const std::vector<std::unique_ptr<Server>>& servers() const { return servers_; }

  // Starts every server (throws Error naming the endpoint that failed); served(s) is
  // called for each once it listens.
  void start_servers(const std::function<void(const Server&)>& served = {});
  // Scans in real time every scan_period_us() at rt_priority(); after_scan runs on the
  // scan thread outside the PLC lock.
  void start_scanning(std::function<void()> after_scan = {});
  RealTimeLoop* loop() { return loop_.get(); }
  // Servers first (no client writes into a stopping PLC), then the scans, then the store
  // writes its last image. Idempotent; the destructor calls it.
  void stop();

 private:
  void run_in_lockstep(const std::string& config_path, const CellOverrides& o, const CellClock& clock);

  // Before soft_: the cell's engine, which scans the twin, goes first.
  std::unique_ptr<SoftCell> twin_;
  std::unique_ptr<SoftCell> soft_;
  std::unique_ptr<online::ChangeService> changes_;  // before the servers, which use it
  std::map<std::string, Settings> server_settings_;
  uint64_t scan_us_ = 0;
  int rt_priority_ = 0;
  PersistSettings persist_;
  std::unique_ptr<persist::Persister> persister_;
  std::vector<std::unique_ptr<Server>> servers_;
  std::unique_ptr<RealTimeLoop> loop_;
};

}  // namespace plc_cell
