#pragma once
// The cell YAML: program, scan settings, retentive ranges, named signals and the
// simulated cell's input signals. docs/cell-config.md describes every key.
#include <cstdint>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/cell_clock.h"
#include "plc_cell/config/register_groups.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/native/engine_choice.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

class ErrorList;

struct SimInputDef {
  std::string name;  // signal name or address as written
  uint32_t x = 0;
  enum class Kind { Pulse, Steps, Follow } kind = Kind::Pulse;
  uint64_t period_us = 0, width_us = 0, delay_us = 0;  // Pulse
  std::vector<std::pair<uint64_t, bool>> steps;        // Steps
  Address source{};                                     // Follow
  uint64_t on_delay_us = 0, off_delay_us = 0;
  bool invert = false;
};

struct TimerBaseRange {
  uint32_t first, last, base_us;
};

// plc.persist: where the retentive ranges survive restarts (docs/reliability.md).
struct PersistSettings {
  std::string file;                // "" = off
  uint64_t interval_us = 100000;   // power-cut window: fdatasync at least this often
  bool sync_writes = true;         // client writes are acknowledged only once on disk
};

struct CellConfig {
  std::string file;  // where it was read from ("" for text)
  std::string name = "cell";
  std::string program;  // absolute or relative to the config's folder, as resolved
  uint64_t scan_period_us = 1000;
  uint64_t watchdog_us = 200000;
  EngineChoice engine = kDefaultEngine;  // plc.engine
  std::vector<AreaRange> retentive = default_retentive();
  std::vector<TimerBaseRange> timer_bases;
  PersistSettings persist;
  std::vector<std::pair<std::string, Address>> signals;  // in file order
  std::vector<SimInputDef> sim_inputs;
  std::vector<RegisterGroup> registers;  // ~registers/<group> on plc_node
  YAML::Node document;  // the whole file, for subsystems that read their own sections
  CellClock clock;      // from whoever builds the cell (SoftCell), not from the file

  static std::vector<AreaRange> default_retentive();
  // Looks a name up among the signals, or parses it as an address.
  Address resolve(const std::string& name_or_address) const;
};

// The top-level keys of a cell file besides the core's (cell, plc, signals, registers,
// simulation) are `sections`: those the cell's extensions claim (config/cell_extension.h,
// SoftCell::sections(), Cell::sections()); a key no one claims is an error.
// These throw SourceError naming file:line:column and the key, listing every error of the file.
CellConfig load_cell_config(const std::string& path, const std::set<std::string>& sections);
CellConfig parse_cell_config(const std::string& yaml_text, const std::string& file,
                             const std::set<std::string>& sections);
// The same, keeping the errors of each section in errors and returning what could be read
// (SoftCell goes on with the subsystems' sections). Still throws when the file cannot be
// read or is not YAML: then there is nothing to go on with.
CellConfig load_cell_config(const std::string& path, ErrorList* errors, const std::set<std::string>& sections);
CellConfig parse_cell_config(const std::string& yaml_text, const std::string& file, ErrorList* errors,
                             const std::set<std::string>& sections);

// "1.5s", "250ms", "100us", "2" (seconds); throws Error.
uint64_t parse_duration_us(const std::string& text);

}  // namespace plc_cell
