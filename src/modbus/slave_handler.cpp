#include "plc_cell/modbus/slave_handler.h"

#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <memory>
#include <cerrno>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/slave_map.h"

namespace plc_cell {
namespace modbus {

namespace {

uint16_t be16(const uint8_t* p) { return uint16_t(p[0] << 8 | p[1]); }

struct Range {
  Table table = Table::Coils;
  uint32_t addr = 0, count = 0;
  bool ok = false;
  Run run;
};
Range span(Table t, uint32_t addr, uint32_t count) {
  Range r;
  r.table = t;
  r.addr = addr;
  r.count = count;
  return r;
}

// Bounds the scratch buffers: no valid request spans more than this.
constexpr uint32_t kMaxSpan = 65536;

void load_bits(const Memory& m, const Range& r, uint8_t* dst) {
  const uint8_t* src = m.bits(r.run.area) + r.run.index;  // raw cells: a tight, vectorised loop
  for (uint32_t i = 0; i < r.count; ++i) dst[i] = src[i] & kBitState;
}
void load_words(const Memory& m, const Range& r, uint16_t* dst) {
  const uint16_t* w = m.words(r.run.area) + r.run.index;
  for (uint32_t i = 0; i < r.count; ++i) dst[i] = w[i];
}
// Only changed elements are written: a refused request (exception) stores nothing.
void store_bits(Memory& m, const Range& r, const uint8_t* src) {
  for (uint32_t i = 0; i < r.count; ++i)
    if (bool(src[i]) != m.bit(r.run.area, r.run.index + i)) m.set_bit(r.run.area, r.run.index + i, src[i] != 0);
}
void store_words(Memory& m, const Range& r, const uint16_t* src) {
  uint16_t* w = m.words(r.run.area) + r.run.index;
  for (uint32_t i = 0; i < r.count; ++i)
    if (w[i] != src[i]) w[i] = src[i];
}

// libmodbus applies a write to the mapping and sends the reply in one call. With
// persistence on, the reply must wait until the write is durable: modbus_reply then
// writes into one end of a socket pair, and the bytes go to the peer after commit().
class HeldReply {
 public:
  explicit HeldReply(modbus_t* ctx) : ctx_(ctx), real_(modbus_get_socket(ctx)) {
    if (::socketpair(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0, sv_) != 0) sv_[0] = sv_[1] = -1;
    else modbus_set_socket(ctx_, sv_[0]);
  }
  ~HeldReply() {
    restore();
    for (int fd : sv_)
      if (fd >= 0) ::close(fd);
  }
  bool ok() const { return sv_[0] >= 0; }
  void restore() { modbus_set_socket(ctx_, real_); }
  // Sends what modbus_reply wrote. A socket gets MSG_NOSIGNAL; a serial line plain write().
  int release() {
    restore();
    uint8_t buf[MODBUS_MAX_ADU_LENGTH];
    const ssize_t n = ::recv(sv_[1], buf, sizeof buf, MSG_DONTWAIT);
    if (n <= 0) return n == 0 || errno == EAGAIN ? 0 : -1;
    ssize_t w = ::send(real_, buf, size_t(n), MSG_NOSIGNAL);
    if (w < 0 && errno == ENOTSOCK) w = ::write(real_, buf, size_t(n));
    return w == n ? int(n) : -1;
  }

 private:
  modbus_t* ctx_;
  int real_;
  int sv_[2] = {-1, -1};
};

// Word-store index of RC back to the counter it belongs to (C200.. take two words).
uint32_t rc_counter(uint32_t w) { return w < kFirst32BitCounter ? w : kFirst32BitCounter + (w - kFirst32BitCounter) / 2; }

bool may_write(const WritableRanges* w, const Range& r) {
  if (!w || w->everything()) return true;
  if (r.run.area != Area::RC) return w->allows(r.run.area, r.run.index, r.count);
  const uint32_t first = rc_counter(r.run.index), last = rc_counter(r.run.index + r.count - 1);
  return w->allows(Area::RC, first, last - first + 1);
}

}  // namespace

bool supported_function(uint8_t fc) {
  switch (fc) {
    case 1: case 2: case 3: case 4: case 5: case 6: case 15: case 16: case 23: return true;
    default: return false;
  }
}

int handle_request(modbus_t* ctx, Plc& plc, const uint8_t* req, int len, const WritableRanges* writable) {
  const int h = modbus_get_header_length(ctx);
  if (len < h + 1) return -1;
  const uint8_t fc = req[h];
  if (!supported_function(fc) || len < h + 5)
    return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  const uint16_t addr = be16(req + h + 1), n = be16(req + h + 3);

  Range rd, wr;  // read range, write range (FC23 has both)
  bool has_rd = false, has_wr = false;
  switch (fc) {
    case 1: rd = span(Table::Coils, addr, n); has_rd = true; break;
    case 2: rd = span(Table::DiscreteInputs, addr, n); has_rd = true; break;
    case 3: rd = span(Table::HoldingRegisters, addr, n); has_rd = true; break;
    case 4: rd = span(Table::InputRegisters, addr, n); has_rd = true; break;
    case 5: wr = span(Table::Coils, addr, 1); has_wr = true; break;
    case 6: wr = span(Table::HoldingRegisters, addr, 1); has_wr = true; break;
    case 15: wr = span(Table::Coils, addr, n); has_wr = true; break;
    case 16: wr = span(Table::HoldingRegisters, addr, n); has_wr = true; break;
    case 23:
      if (len < h + 9) return modbus_reply_exception(ctx, req, MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);
      rd = span(Table::HoldingRegisters, addr, n);
      wr = span(Table::HoldingRegisters, be16(req + h + 5), be16(req + h + 7));
      has_rd = has_wr = true;
      break;
  }

  thread_local std::vector<uint8_t> bits(kMaxSpan);
  thread_local std::vector<uint16_t> words(kMaxSpan);

  std::unique_ptr<HeldReply> held;
  if (has_wr && plc.has_durability()) {
    held = std::make_unique<HeldReply>(ctx);
    if (!held->ok()) return -1;
  }
  const int replied = plc.locked([&](ScanEngine&, Memory& m) {
    if (has_rd) rd.ok = resolve(m, rd.table, rd.addr, rd.count, &rd.run);
    if (has_wr) wr.ok = resolve(m, wr.table, wr.addr, wr.count, &wr.run) && may_write(writable, wr);
    // An unmapped range leaves the table empty in the mapping: libmodbus then
    // checks the quantity first (exception 03) and the address next (02).
    modbus_mapping_t mp{};
    const bool all_ok = (!has_rd || rd.ok) && (!has_wr || wr.ok);
    if (all_ok) {
      const uint32_t lo = has_rd && has_wr ? std::min(rd.addr, wr.addr) : (has_rd ? rd.addr : wr.addr);
      const uint32_t hi = has_rd && has_wr ? std::max(rd.addr + rd.count, wr.addr + wr.count)
                                           : (has_rd ? rd.addr + rd.count : wr.addr + wr.count);
      const Table t = has_rd ? rd.table : wr.table;
      const int nb = int(hi - lo);
      switch (t) {
        case Table::Coils: mp.start_bits = int(lo); mp.nb_bits = nb; mp.tab_bits = bits.data(); break;
        case Table::DiscreteInputs:
          mp.start_input_bits = int(lo); mp.nb_input_bits = nb; mp.tab_input_bits = bits.data(); break;
        case Table::InputRegisters:
          mp.start_input_registers = int(lo); mp.nb_input_registers = nb;
          mp.tab_input_registers = words.data(); break;
        case Table::HoldingRegisters:
          mp.start_registers = int(lo); mp.nb_registers = nb; mp.tab_registers = words.data(); break;
      }
      const bool is_bits = t == Table::Coils || t == Table::DiscreteInputs;
      for (const Range* r : {has_rd ? &rd : nullptr, has_wr ? &wr : nullptr}) {
        if (!r) continue;
        if (is_bits) load_bits(m, *r, bits.data() + (r->addr - lo));
        else load_words(m, *r, words.data() + (r->addr - lo));
      }
      const int rc = modbus_reply(ctx, req, len, &mp);
      if (has_wr) {
        if (is_bits) store_bits(m, wr, bits.data() + (wr.addr - lo));
        else store_words(m, wr, words.data() + (wr.addr - lo));
      }
      return rc;
    }
    return modbus_reply(ctx, req, len, &mp);
  });
  if (!held) return replied;
  if (replied < 0) return replied;
  plc.commit();
  return held->release();
}

}  // namespace modbus
}  // namespace plc_cell
