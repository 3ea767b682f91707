#pragma once
// The cell YAML's `servers:` section: which protocol servers a cell starts and their safety
// settings (docs/security.md). Command-line options and plc_node parameters override each
// field; with neither, nothing is served.
#include <string>

#include "plc_cell/config/cell_config.h"

namespace plc_cell {

struct FatekServerSettings {
  std::string tcp, serial;  // "" = off
  int station = 1;
  std::string writable = "all";
  int max_connections = 8;
  int idle_timeout_ms = 60000;
};

struct ModbusServerSettings {
  std::string tcp, rtu;  // "" = off
  int id = 1;
  std::string writable = "all";
  int max_connections = 16;
  int idle_timeout_ms = 60000;
};

struct ServerSettings {
  FatekServerSettings fatek;
  ModbusServerSettings modbus;
};

// Reads cfg.document["servers"]; throws SourceError naming file:line and the key.
ServerSettings parse_server_settings(const CellConfig& cfg);

}  // namespace plc_cell
