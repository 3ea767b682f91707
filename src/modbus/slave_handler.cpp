#include "plc_cell/modbus/slave_handler.h"

#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/rtu_frame.h"
#include "plc_cell/modbus/slave_map.h"

namespace plc_cell {
namespace modbus {

namespace {

uint16_t be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }

PduAnswer exception(const uint8_t* pdu, uint8_t code, uint8_t* rsp) {
  rsp[0] = uint8_t(pdu[0] | 0x80);
  rsp[1] = code;
  PduAnswer a;
  a.length = 2;
  a.exception = code;
  return a;
}

// What one request asks for, decoded and checked before the lock is taken.
struct Decoded {
  Table table = Table::Coils;
  bool read = false, write = false;
  uint16_t rd_addr = 0, rd_count = 0, wr_addr = 0, wr_count = 0;
  const uint8_t* values = nullptr;  // FC 15/16/23: packed bits or big-endian words
  bool single_coil_on = false;      // FC 5
  uint16_t single_value = 0;        // FC 6
};

// 0 when the PDU is a well-formed request, else the exception code (01 or 03):
// the checks of the protocol's state diagrams, in its order (function, then
// quantity and length); the address (02) needs the memory map and comes later.
uint8_t decode(const uint8_t* p, int len, Decoded* d) {
  const uint8_t fc = p[0];
  if (!supported_function(fc)) return MODBUS_EXCEPTION_ILLEGAL_FUNCTION;
  constexpr uint8_t kBad = MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE;
  if (len < 5) return kBad;
  const uint16_t addr = be16(p + 1), n = be16(p + 3);
  switch (fc) {
    case 1: case 2: case 3: case 4: {
      const int max = fc <= 2 ? kMaxReadBits : kMaxReadRegisters;
      if (len != 5 || n < 1 || n > max) return kBad;
      d->table = fc == 1 ? Table::Coils : fc == 2 ? Table::DiscreteInputs
               : fc == 3 ? Table::HoldingRegisters : Table::InputRegisters;
      d->read = true;
      d->rd_addr = addr;
      d->rd_count = n;
      return 0;
    }
    case 5:
      if (len != 5 || (n != 0x0000 && n != 0xFF00)) return kBad;
      d->table = Table::Coils;
      d->write = true;
      d->wr_addr = addr;
      d->wr_count = 1;
      d->single_coil_on = n == 0xFF00;
      return 0;
    case 6:
      if (len != 5) return kBad;
      d->table = Table::HoldingRegisters;
      d->write = true;
      d->wr_addr = addr;
      d->wr_count = 1;
      d->single_value = n;
      return 0;
    case 15: case 16: {
      if (len < 6) return kBad;
      const int bc = p[5];
      const bool ok = fc == 15 ? (n >= 1 && n <= kMaxWriteBits && bc == (n + 7) / 8)
                               : (n >= 1 && n <= kMaxWriteRegisters && bc == 2 * n);
      if (!ok || len != 6 + bc) return kBad;
      d->table = fc == 15 ? Table::Coils : Table::HoldingRegisters;
      d->write = true;
      d->wr_addr = addr;
      d->wr_count = n;
      d->values = p + 6;
      return 0;
    }
    case 23: {
      if (len < 10) return kBad;
      const uint16_t wa = be16(p + 5), wn = be16(p + 7);
      const int bc = p[9];
      if (n < 1 || n > kMaxReadRegisters || wn < 1 || wn > kMaxRwWriteRegisters || bc != 2 * wn || len != 10 + bc)
        return kBad;
      d->table = Table::HoldingRegisters;
      d->read = d->write = true;
      d->rd_addr = addr;
      d->rd_count = n;
      d->wr_addr = wa;
      d->wr_count = wn;
      d->values = p + 10;
      return 0;
    }
  }
  return MODBUS_EXCEPTION_ILLEGAL_FUNCTION;
}

}  // namespace

bool supported_function(uint8_t fc) {
  switch (fc) {
    case 1: case 2: case 3: case 4: case 5: case 6: case 15: case 16: case 23: return true;
    default: return false;
  }
}

PduAnswer answer_pdu(Plc& plc, const uint8_t* pdu, int len, uint8_t* rsp, const WritableRanges* writable,
                     const MapProfile& map) {
  if (len < 1) return PduAnswer{};
  Decoded d;
  if (const uint8_t code = decode(pdu, len, &d)) return exception(pdu, code, rsp);
  // A range past 65535 is an address error (02) in the protocol's diagrams.
  if ((d.read && uint32_t(d.rd_addr) + d.rd_count > 65536u) || (d.write && uint32_t(d.wr_addr) + d.wr_count > 65536u))
    return exception(pdu, MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS, rsp);

  // Values to write, unpacked before the lock: one byte per bit, host-order words.
  uint8_t wbits[kMaxWriteBits];
  uint16_t wwords[kMaxWriteRegisters];
  if (d.write) {
    if (pdu[0] == 5) wbits[0] = d.single_coil_on;
    else if (pdu[0] == 6) wwords[0] = d.single_value;
    else if (pdu[0] == 15)
      for (int i = 0; i < d.wr_count; ++i) wbits[i] = (d.values[i / 8] >> (i % 8)) & 1;
    else
      for (int i = 0; i < d.wr_count; ++i) wwords[i] = be16(d.values + 2 * i);
  }
  uint8_t rbits[kMaxReadBits];
  uint16_t rwords[kMaxReadRegisters];

  // The lock: the map resolves the request (the FBs user map lives in PLC memory), stores
  // the write and copies the read. One scan's state; a refused request stores nothing.
  // Nothing here waits on a client.
  Transfer t;
  t.table = d.table;
  t.rd_addr = d.rd_addr;
  t.rd_count = d.read ? d.rd_count : 0;
  t.wr_addr = d.wr_addr;
  t.wr_count = d.write ? d.wr_count : 0;
  t.wbits = wbits;
  t.wwords = wwords;
  t.rbits = rbits;
  t.rwords = rwords;
  const bool bits = t.bits();
  const bool mapped =
      plc.locked([&](ScanEngine& e, Memory& m) { return map.transfer(e, m, t, writable); });
  if (!mapped) return exception(pdu, MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS, rsp);
  if (d.write) plc.commit();  // durable before it is acknowledged

  PduAnswer a;
  a.accepted = true;
  rsp[0] = pdu[0];
  if (d.read) {
    int nbytes;
    if (bits) {
      nbytes = (d.rd_count + 7) / 8;
      std::memset(rsp + 2, 0, size_t(nbytes));
      for (int i = 0; i < d.rd_count; ++i) rsp[2 + i / 8] |= uint8_t(rbits[i] << (i % 8));
    } else {
      nbytes = 2 * d.rd_count;
      for (int i = 0; i < d.rd_count; ++i) {
        rsp[2 + 2 * i] = uint8_t(rwords[i] >> 8);
        rsp[3 + 2 * i] = uint8_t(rwords[i]);
      }
    }
    rsp[1] = uint8_t(nbytes);
    a.length = 2 + nbytes;
  } else {  // writes echo function, address and quantity (FC 5/6: the value)
    std::memcpy(rsp + 1, pdu + 1, 4);
    a.length = 5;
  }
  return a;
}

int handle_request(modbus_t* ctx, Plc& plc, const uint8_t* req, int len, const WritableRanges* writable,
                   const MapProfile& map) {
  const int h = modbus_get_header_length(ctx);
  const bool rtu = h == 1;
  const int tail = rtu ? 2 : 0;
  if (len < h + 1 + tail) return -1;
  uint8_t out[MODBUS_TCP_MAX_ADU_LENGTH];
  const PduAnswer a = answer_pdu(plc, req + h, len - h - tail, out + (rtu ? 1 : 7), writable, map);
  if (a.length == 0) return -1;
  int n;
  if (rtu) {
    if (req[0] == 0) return 0;  // broadcast: executed, never answered
    out[0] = req[0];
    n = 1 + a.length;
    const uint16_t crc = crc16(out, size_t(n));
    out[n++] = uint8_t(crc & 0xFF);  // the CRC goes low byte first
    out[n++] = uint8_t(crc >> 8);
  } else {
    out[0] = req[0];
    out[1] = req[1];
    out[2] = out[3] = 0;
    out[4] = uint8_t((a.length + 1) >> 8);
    out[5] = uint8_t(a.length + 1);
    out[6] = req[6];
    n = 7 + a.length;
  }
  const int fd = modbus_get_socket(ctx);
  ssize_t w = ::send(fd, out, size_t(n), MSG_NOSIGNAL);
  if (w < 0 && errno == ENOTSOCK) w = ::write(fd, out, size_t(n));
  return w == n ? n : -1;
}

}  // namespace modbus
}  // namespace plc_cell
