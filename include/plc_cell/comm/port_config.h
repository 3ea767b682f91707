#pragma once
// The cell YAML's `ports:` section: COM ports 1..4, each one line whichever instruction
// (FUN150 Modbus master, FUN151 FATEK link) uses it, as on an FBs-PLC.
//
//   ports:
//     timeout: 500ms                     # FUN151's reply time-out (default 500 ms)
//     1: {serial: /dev/ttyS1:9600:7E1}   # DEVICE[:BAUD[:FORMAT]], default 9600 7E1
//     2: {tcp: 10.0.0.5:502}             # a serial server or a slave on Ethernet
//
// The older spellings `fatek: {timeout_ms, ports: {N: LINE}}` and `modbus: {ports: {N:
// {rtu | tcp}}}` are still read and feed the same ports; a port declared in two places
// must name the same line (a port is one physical port).
#include <map>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/error_list.h"
#include "plc_cell/io/com_port.h"

namespace plc_cell {

struct PortSettings {
  int timeout_ms = 500;
  std::map<int, ComLine> lines;  // port 1..4 -> its line
};

// Every error of the three sections into errors (file:line:column, the key and why), and
// what could be read.
PortSettings read_port_settings(const YAML::Node& document, const std::string& file, ErrorList* errors);
// The same, throwing one SourceError that lists them all.
PortSettings read_port_settings(const YAML::Node& document, const std::string& file);

}  // namespace plc_cell
