#pragma once
// A kind of protocol server (FATEK, Modbus, ...) as a cell knows it: the settings it takes
// and how its servers are made from them. The cell YAML's `servers.<kind>.<key>`,
// plc_node's `~<kind>_<key>` and `plc_cell run --<kind>-<key>` are one setting written
// three ways; merge_server_settings reads the YAML, applies the front end's overrides on
// top and checks every value once, so a new server kind is one schema and one factory and
// every front end offers it (docs/architecture.md, "How to add a protocol server").
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/io/server.h"

namespace plc_cell {

class Plc;
struct CellConfig;
class CellExtension;
class ProgramChanges;

// What a server kind's factory may use besides its settings: the PLC, and for a server
// that shows the whole cell (the monitor, docs/monitor-api.md) the cell's config, its
// extensions, its program file and its servers. A bare Plc converts to a context with
// only the PLC (the protocol servers need no more).
struct ServerContext {
  ServerContext(Plc& p) : plc(p) {}  // NOLINT: implicit on purpose, see above
  Plc& plc;
  const CellConfig* config = nullptr;                                 // nullptr: no cell file
  const std::vector<std::unique_ptr<CellExtension>>* extensions = nullptr;
  std::string program_path;
  std::function<std::vector<const Server*>()> servers;  // every server of the cell, when set
  ProgramChanges* changes = nullptr;  // changes of the running program (online change), when offered
};

enum class SettingType {
  Text,        // free text
  HostPort,    // HOST:PORT
  SerialLine,  // DEVICE[:BAUD[:FORMAT]], FORMAT defaulting to SettingSpec::format
  Integer,     // in [lo, hi]
  Duration,    // "60s", "250ms", a bare number of seconds; lo/hi in microseconds
  Writable,    // "D0-D99,M800", "all" or "none" (a YAML list is joined)
  Boolean,     // true/false (also on/off, 1/0), kept as "true" or "false"
};

struct SettingSpec {
  std::string key;  // snake_case: servers.fatek.idle_timeout, ~fatek_idle_timeout, --fatek-idle-timeout
  SettingType type = SettingType::Text;
  std::string fallback;      // as it would be written; "" = off for endpoints
  int64_t lo = 0, hi = 0;    // Integer bounds; Duration bounds in us
  std::string format;        // SerialLine: the default character framing ("7E1", "8E1")
  bool repeatable = false;   // several values (the command line repeats the option)
  std::string cli_alias;     // an option name the command line also takes ("station")
  std::string retired_ros;   // a parameter name no longer read: refused, naming this one
  std::string help;          // one line for --help and the docs' tables
};

// Where a front end puts a value: "--modbus-id", "~modbus_id". values holds the option's
// every occurrence (repeatable settings), each as text.
struct SettingOverride {
  std::string kind, key;
  std::vector<std::string> values;
  std::string origin;
};

// One server kind's settings after the merge: every key of its schema has a checked value.
class Settings {
 public:
  Settings() = default;
  Settings(std::string kind, std::map<std::string, std::vector<std::string>> values)
      : kind_(std::move(kind)), values_(std::move(values)) {}
  const std::string& kind() const { return kind_; }
  // The value ("" for an endpoint that is off); all() for a repeatable key.
  const std::string& text(const std::string& key) const;
  const std::vector<std::string>& all(const std::string& key) const;
  int64_t integer(const std::string& key) const;
  uint64_t duration_us(const std::string& key) const;
  WritableRanges writable(const std::string& key) const;
  bool boolean(const std::string& key) const { return text(key) == "true"; }

 private:
  std::string kind_;
  std::map<std::string, std::vector<std::string>> values_;
};

struct ServerKind {
  std::string name;   // "fatek": the YAML key, the prefix of options and parameters
  std::string title;  // "FATEK slave (docs/fatek.md)"
  std::vector<SettingSpec> settings;
  // The servers these settings ask for (none when every endpoint is off), not started.
  // Throws plc_cell::Error on a combination the settings' own checks cannot see.
  std::function<std::vector<std::unique_ptr<Server>>(const ServerContext&, const Settings&)> make;

  const SettingSpec* spec(const std::string& key) const;
  // "--fatek-idle-timeout", "~fatek_idle_timeout".
  std::string option(const SettingSpec& s) const;
  std::string parameter(const SettingSpec& s) const;
};

// The cell YAML's `servers:` section read against kinds, then overrides applied in order:
// one Settings per kind. A YAML error is a SourceError at file:line:column naming
// servers.<kind>.<key>; an override's error names its origin and value.
std::map<std::string, Settings> merge_server_settings(const std::vector<ServerKind>& kinds, const CellConfig& cfg,
                                                      const std::vector<SettingOverride>& overrides = {});

// Checks text as a value of spec and returns it in the form Settings keeps; throws
// plc_cell::Error saying why.
std::string check_setting(const SettingSpec& spec, const std::string& text);

// A schema's entries, written as one line each.
SettingSpec setting(std::string key, SettingType type, std::string help, std::string fallback = "");
SettingSpec serial_setting(std::string key, std::string format, std::string help);
SettingSpec integer_setting(std::string key, int64_t fallback, int64_t lo, int64_t hi, std::string help);
SettingSpec duration_setting(std::string key, std::string fallback, int64_t lo_us, int64_t hi_us, std::string help);
// What clients may do, the same for every server kind (docs/security.md): writable
// (default all), max_connections (this kind's default; 1-1024) and idle_timeout (60s).
std::vector<SettingSpec> client_limits(int max_connections);

}  // namespace plc_cell
