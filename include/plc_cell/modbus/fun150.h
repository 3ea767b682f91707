#pragma once
// FUN150 M-BUS: the PLC as a Modbus master from its program (spec §3.6, manual
// [M:4753-5010]). The scan never waits: each COM port (io/com_port.h, shared with
// FUN151) has a thread doing one transaction at a time; the instruction hands it the
// next transaction of its table and applies the result on a later scan, under the
// scan's lock.
//
//   ORG  EN          ; 0->1 starts one pass over the table
//   LD   A/R         ; 0 = RTU; 1 = ASCII (not supported by libmodbus: result 7)
//   LD   ABT         ; 1 aborts and releases the port
//   FUN  150 Pt=1 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2
#include <map>
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/function_table.h"
#include "plc_cell/io/com_ports.h"

namespace plc_cell {
namespace modbus {

struct MbusPort {
  std::string tcp;  // HOST:PORT (unit = the table's station), or
  std::string rtu;  // DEVICE[:BAUD[:FORMAT]], default 9600 8E1
};

// The cell YAML's older `modbus: ports: {1: {rtu: ...}, 2: {tcp: ...}}`, every key and
// line checked; an error names file:line:column and the key. The cell reads it as a
// spelling of its `ports:` section (comm/port_config.h).
std::map<int, MbusPort> parse_mbus_ports(const YAML::Node& modbus_section, const std::string& file);

// The line of one older `modbus.ports` entry (RTU defaults to 8E1).
ComLine mbus_line(const MbusPort& p);

class MbusEngine;

// Adds FUN150 on the cell's COM ports (shared with FUN151); the returned engine must
// outlive every Plc built from t.
std::shared_ptr<MbusEngine> add_fun150_on(FunctionTable& t, const ComPorts& ports);
// The same with a COM port of its own for each of ports.
std::shared_ptr<MbusEngine> add_fun150(FunctionTable& t, std::map<int, MbusPort> ports);

// Result codes in WR+0's high byte [M:4968-4984].
namespace mbus_result {
constexpr int kOk = 0, kLength = 2, kCommand = 3, kDataType = 4, kReference = 5, kInconsistent = 6, kPort = 7,
              kTable = 8, kNoResponse = 0xA, kCommError = 0xB;
}

}  // namespace modbus
}  // namespace plc_cell
