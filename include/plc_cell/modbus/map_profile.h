#pragma once
// Which map a Modbus slave serves, as a strategy: the FBs manual's (slave_map.h) or the
// TRi FMD's Table 14.1 (tri_map.h). It is chosen once, where the server kind is built
// (servers.modbus `map:`), and handed to the servers, which never ask which one it is: the
// request handler (slave_handler.h) decodes and checks a request and leaves the transfer
// to the profile. A new map is one more MapProfile and its name in map_profile().
#include <cstdint>
#include <string>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/modbus/slave_map.h"

namespace plc_cell {
namespace modbus {

// One request's transfer, decoded and checked (function, quantity, length) by the handler.
struct Transfer {
  Table table = Table::HoldingRegisters;  // the function's table (FC 23: holding registers)
  uint32_t rd_addr = 0, rd_count = 0;     // count 0: no read
  uint32_t wr_addr = 0, wr_count = 0;     // count 0: no write
  const uint8_t* wbits = nullptr;         // the values to write, one byte per bit, or
  const uint16_t* wwords = nullptr;       // host-order words
  uint8_t* rbits = nullptr;               // where the read goes, likewise
  uint16_t* rwords = nullptr;
  bool bits() const { return table == Table::Coils || table == Table::DiscreteInputs; }
};

class MapProfile {
 public:
  virtual ~MapProfile() = default;
  virtual const char* name() const = 0;  // "fbs", "tri"
  // With the PLC lock held: every element of the read and the write is resolved and the
  // writes checked against writable (null: all) first; false (exception 02) when any is
  // unmapped or not writable, and then nothing is changed. Writes go before reads (FC 23
  // reads what it wrote, the protocol's order).
  virtual bool transfer(ScanEngine& e, Memory& m, const Transfer& t, const WritableRanges* writable) const = 0;
};

const MapProfile& fbs_map_profile();
const MapProfile& tri_map_profile();
// "fbs" or "tri"; throws plc_cell::Error naming the text otherwise.
const MapProfile& map_profile(const std::string& name);

}  // namespace modbus
}  // namespace plc_cell
