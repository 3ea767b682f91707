#pragma once
// Answers one Modbus request from PLC memory. The request is decoded and checked
// (function, quantity, byte count, length) with no lock held; the PLC lock is taken
// only to resolve the address and copy the data in or out; the reply is built and
// sent after the lock is released. A request can therefore never hold up the scan.
//
// Why the replies are built here and not by libmodbus's modbus_reply: for a quantity
// or byte-count error (exception 03) and some address errors, modbus_reply first
// sleeps its response timeout and flushes the line before it answers (500 ms on TCP
// by default), and on TCP that flush also reads away whatever request the client
// pipelined next. Nine function codes are a page of code; libmodbus keeps what it
// does well here: opening, binding and configuring sockets and serial lines.
#include <cstdint>

#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/modbus/map_profile.h"

#include <modbus/modbus.h>

namespace plc_cell {

class Plc;

namespace modbus {

// FC 1, 2, 3, 4, 5, 6, 15, 16, 23; anything else gets exception 01.
bool supported_function(uint8_t fc);

// The limits of the Modbus Application Protocol (V1.1b3, section 6).
constexpr int kMaxReadBits = 2000;          // FC 1, 2
constexpr int kMaxReadRegisters = 125;      // FC 3, 4, 23 (read part)
constexpr int kMaxWriteBits = 1968;         // FC 15
constexpr int kMaxWriteRegisters = 123;     // FC 16
constexpr int kMaxRwWriteRegisters = 121;   // FC 23 (write part)
constexpr int kMaxPdu = 253;

struct PduAnswer {
  int length = 0;         // bytes of reply PDU written (function code first)
  bool accepted = false;  // false: the reply is an exception
  uint8_t exception = 0;  // the exception code when !accepted
};

// Answers one request PDU (function code + data, no MBAP header, no CRC) into
// rsp[kMaxPdu]. A rejected request changes nothing. A write is committed (see
// Plc::commit) before this returns, so the reply may go out at once.
// map: the profile served (map_profile.h).
PduAnswer answer_pdu(Plc& plc, const uint8_t* pdu, int len, uint8_t* rsp, const WritableRanges* writable = nullptr,
                     const MapProfile& map = fbs_map_profile());

// req/len: a whole ADU as the context's transport frames it (MBAP + PDU for TCP,
// slave id + PDU + CRC for RTU; the CRC is not checked here). Answers on the
// context's socket; an RTU broadcast (slave 0) is executed and not answered.
// Returns the bytes sent, 0 for no reply, -1 when the reply could not be sent.
// A write outside `writable` (null: everything writable) is answered with exception 02,
// as an unmapped address, and changes nothing.
int handle_request(modbus_t* ctx, Plc& plc, const uint8_t* req, int len, const WritableRanges* writable = nullptr,
                   const MapProfile& map = fbs_map_profile());

}  // namespace modbus
}  // namespace plc_cell
