#pragma once
// FUN151 CLINK (manual ch. 13, spec 3.2-3.4): MD0 makes the PLC master of a FATEK CPU
// link driven by a table in memory; MD1 sends (and optionally receives) free-protocol
// messages; MD2 receives them (and optionally replies). Transactions run on the COM port's
// thread (io/com_port.h, shared with FUN150) so the scan never waits for the line; the
// instruction polls on later scans.
//
//   ORG EN / LD PAU / LD ABT / FUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2
//
// MD3 (high-speed link, wire format undocumented) is not implemented: ERR with result 3.
#include <array>
#include <map>
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/function_table.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/io/com_ports.h"

namespace plc_cell {
namespace fatek {

// Result codes of WR+0 high byte (manual ch. 13).
enum class ClinkResult : uint8_t {
  Ok = 0, Length = 2, Command = 3, DataType = 4, Reference = 5, Inconsistent = 6, Timeout = 0xA, BadData = 0xB
};

// The cell YAML's older `fatek:` section: `ports: {1: "/dev/ttyS1:9600:7E1", 2: "tcp:HOST:PORT"}`,
// optional `timeout_ms` (default 500, the FBs R4147 default of 50 x 0.01 s). The cell
// reads it as a spelling of its `ports:` section (comm/port_config.h).
struct ClinkSettings {
  int timeout_ms = 500;
  std::map<int, std::string> ports;  // port 1..4 -> its line, as written
};
// Every key and line is checked here (an error names file:line:column and the key), so
// `plc_cell check` refuses what the running cell would, without opening a line.
ClinkSettings read_clink_settings(const YAML::Node& fatek_section, const std::string& file);

// The line of one older `fatek.ports` entry ("tcp:HOST:PORT" or a serial line, 7E1).
ComLine clink_line(const std::string& where);

// FUN151's side of ports 1..4 of the master PLC, each a FATEK line to its slaves.
class ClinkPorts {
 public:
  ClinkPorts();
  ~ClinkPorts();
  // FUN151 on the cell's COM ports, shared with FUN150.
  static std::shared_ptr<ClinkPorts> on(const ComPorts& ports, int timeout_ms);
  // The lines of read_clink_settings, each a COM port of its own.
  static std::shared_ptr<ClinkPorts> from_settings(const ClinkSettings& s);
  static std::shared_ptr<ClinkPorts> from_yaml(const YAML::Node& fatek_section, const std::string& file);
  void set_port(std::shared_ptr<ComPort> port, int timeout_ms = 500);
  // A port whose transactions go over t (a port with no line of its own).
  void set_port(int n, std::unique_ptr<Transport> t, int timeout_ms = 500);
  bool has(int n) const;

  struct Port;
  Port* port(int n);

 private:
  void add(std::shared_ptr<ComPort> port, std::unique_ptr<Transport> t, int timeout_ms);
  std::array<std::unique_ptr<Port>, 5> ports_;
};

// Registers FUN151 CLINK (inputs EN, PAU, ABT; operands Pt, MD, SR, WR, ACT, ERR, DN).
void add_clink_function(FunctionTable& t, std::shared_ptr<ClinkPorts> ports);

}  // namespace fatek
}  // namespace plc_cell
