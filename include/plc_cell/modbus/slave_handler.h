#pragma once
// Answers one Modbus request from PLC memory. libmodbus does the framing, the
// quantity/value checks and the reply; we only lend it a mapping that covers
// exactly the requested range, filled from memory under the PLC lock.
#include <cstdint>

#include "plc_cell/core/writable_ranges.h"

#include <modbus/modbus.h>

namespace plc_cell {

class Plc;

namespace modbus {

// FC 1, 2, 3, 4, 5, 6, 15, 16, 23; anything else gets exception 01.
bool supported_function(uint8_t fc);

// req/len as modbus_receive returned them. The whole request runs inside one
// plc.locked(): it sees one scan's state and a rejected request changes nothing.
// Returns modbus_reply's result (-1 when the reply could not be sent).
// A write outside `writable` (null: everything writable) is answered with exception 02,
// as an unmapped address, and changes nothing.
int handle_request(modbus_t* ctx, Plc& plc, const uint8_t* req, int len, const WritableRanges* writable = nullptr);

}  // namespace modbus
}  // namespace plc_cell
