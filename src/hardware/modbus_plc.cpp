#include "plc_cell/hardware/modbus_plc.h"

#include <modbus/modbus.h>

#include <algorithm>
#include <cerrno>
#include <tuple>

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace hardware {

namespace {

// A row of the default map: FBs elements [lo, hi] of an area from Modbus address base.
struct MapRow {
  Area area;
  bool coils;
  uint32_t lo, hi, base;
};
// docs/modbus.md, "Default map" (C200-C255 apart: two registers each).
const MapRow kRows[] = {
    {Area::Y, true, 0, 255, 0},       {Area::X, true, 0, 255, 1000},    {Area::M, true, 0, 2001, 2000},
    {Area::S, true, 0, 999, 6000},    {Area::T, true, 0, 255, 9000},    {Area::C, true, 0, 255, 9500},
    {Area::R, false, 0, 4167, 0},     {Area::R, false, 5000, 5998, 5000}, {Area::D, false, 0, 2998, 6000},
    {Area::RT, false, 0, 255, 9000},  {Area::RC, false, 0, 199, 9500},
};
constexpr uint32_t kLongCounterBase = 9700;  // C200-C255: 9700 + 2 (n - 200), low word first
constexpr uint32_t kLongCounterSegment = 100;
constexpr uint32_t kGap = 8;                 // unrequested elements read through to join two runs
constexpr uint32_t kMaxBits = 2000, kMaxRegisters = 125;

uint32_t elements(const Address& a) {
  if (is_discrete(a.area)) return a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  return a.width == Width::DWord ? 2 : 1;
}

bool closed(int e) { return e == ECONNRESET || e == EPIPE || e == EBADF || e == ENOTCONN; }

}  // namespace

ModbusPlace fbs_modbus_place(const Address& a) {
  const uint32_t n = elements(a);
  if (a.area == Area::RC && a.width == Width::DWord && a.index >= kFirst32BitCounter) {
    if (a.index >= kCounterCount) throw Error(format_address(a) + ": no such counter");
    return {false, kLongCounterBase + 2 * (a.index - kFirst32BitCounter), 2, kLongCounterSegment};
  }
  if (a.area == Area::RC && a.index + n - 1 >= kFirst32BitCounter)
    throw Error(format_address(a) + ": C200-C255 are 32-bit counters: read them as DRC200-DRC255");
  for (uint32_t row = 0; row < sizeof kRows / sizeof kRows[0]; ++row) {
    const MapRow& r = kRows[row];
    if (r.area != a.area || a.index < r.lo || a.index + n - 1 > r.hi) continue;
    return {r.coils, r.base + a.index - r.lo, n, row};
  }
  throw Error(format_address(a) + " is not in the FBs Modbus map (docs/modbus.md, \"Default map\")");
}

ModbusPlc::ModbusPlc(const std::string& endpoint, bool rtu, int unit, int timeout_ms, int retries)
    : timeout_ms_(timeout_ms), retries_(retries) {
  if (rtu) {
    const SerialSettings s = parse_serial_settings(endpoint, "8E1", 9600);
    ctx_ = modbus_new_rtu(s.device.c_str(), s.baud, s.parity, s.data_bits, s.stop_bits);
    t_ = serial_transport(s);
  } else {
    std::string host;
    int port = 0;
    parse_host_port(endpoint, &host, &port);
    if (port == 0) throw Error("modbus://" + endpoint + ": a port 1..65535 is needed (a Modbus TCP server listens on 502)");
    ctx_ = modbus_new_tcp(host.empty() ? "127.0.0.1" : host.c_str(), port);
    t_ = tcp_transport(endpoint);
  }
  if (!ctx_) throw Error(endpoint + ": " + modbus_strerror(errno));
  modbus_set_slave(ctx_, unit);
  modbus_set_response_timeout(ctx_, uint32_t(timeout_ms / 1000), uint32_t(timeout_ms % 1000) * 1000);
  name_ = std::string("Modbus ") + (rtu ? "RTU " : "") + t_->describe() + " unit " + std::to_string(unit);
}

ModbusPlc::~ModbusPlc() { modbus_free(ctx_); }

template <class F>
void ModbusPlc::transact(const std::string& what, F&& f) {
  with_retries(*t_, retries_, timeout_ms_, &retries_used_, [&] {
    if (!t_->is_open()) t_->open();
    modbus_set_socket(ctx_, t_->fd());
    errno = 0;
    if (f(ctx_) >= 0) return;
    const int e = errno;
    if (e > MODBUS_ENOBASE && e < MODBUS_ENOBASE + 12)
      throw Error(name_ + " answered " + what + " with an exception: " + modbus_strerror(e));
    if (closed(e)) throw ConnectionClosed(name_ + ": " + what + ": " + modbus_strerror(e));
    throw CommError(name_ + ": " + what + ": " + modbus_strerror(e));
  });
}

std::string ModbusPlc::cannot_reach(const Address& a) const {
  try {
    fbs_modbus_place(a);
    return "";
  } catch (const Error& e) {
    return e.what();
  }
}

std::string ModbusPlc::cannot_force() const {
  return "Modbus has no force (no DISABLE flag), so a point it writes is not held: an input lasts until the PLC's "
         "next input refresh";
}

void ModbusPlc::force(const Address& bit, bool) { throw Error(format_address(bit) + ": " + cannot_force()); }

std::vector<uint32_t> ModbusPlc::read(const std::vector<Address>& addrs) {
  std::vector<ModbusPlace> places;
  std::vector<size_t> order;
  for (size_t i = 0; i < addrs.size(); ++i) places.push_back(fbs_modbus_place(addrs[i])), order.push_back(i);
  std::sort(order.begin(), order.end(), [&](size_t x, size_t y) {
    const ModbusPlace &a = places[x], &b = places[y];
    return std::make_tuple(a.coils, a.segment, a.first) < std::make_tuple(b.coils, b.segment, b.first);
  });
  std::vector<uint32_t> out(addrs.size(), 0);
  for (size_t k = 0; k < order.size();) {
    const ModbusPlace& head = places[order[k]];
    const uint32_t limit = head.coils ? kMaxBits : kMaxRegisters;
    uint32_t end = head.first + head.count;
    size_t next = k + 1;
    for (; next < order.size(); ++next) {
      const ModbusPlace& p = places[order[next]];
      const uint32_t new_end = std::max(end, p.first + p.count);
      if (p.coils != head.coils || p.segment != head.segment || p.first > end + kGap || new_end - head.first > limit)
        break;
      end = new_end;
    }
    const uint32_t n = end - head.first;
    std::vector<uint16_t> regs(head.coils ? 0 : n);
    std::vector<uint8_t> bits(head.coils ? n : 0);
    const std::string what = std::string(head.coils ? "FC 01 at coil " : "FC 03 at register ") +
                             std::to_string(head.first) + " x" + std::to_string(n);
    transact(what, [&](modbus_t* c) {
      return head.coils ? modbus_read_bits(c, int(head.first), int(n), bits.data())
                        : modbus_read_registers(c, int(head.first), int(n), regs.data());
    });
    for (size_t j = k; j < next; ++j) {
      const ModbusPlace& p = places[order[j]];
      const uint32_t at = p.first - head.first;
      uint32_t v = 0;
      if (p.coils) {
        for (uint32_t b = 0; b < p.count; ++b) v |= uint32_t(bits[at + b] ? 1 : 0) << b;
      } else {
        v = regs[at] | (p.count == 2 ? uint32_t(regs[at + 1]) << 16 : 0);
      }
      out[order[j]] = v;
    }
    k = next;
  }
  return out;
}

void ModbusPlc::write(const Address& a, uint32_t raw) {
  const ModbusPlace p = fbs_modbus_place(a);
  const std::string what = "the write of " + format_address(a);
  if (p.coils && p.count == 1) {
    transact(what, [&](modbus_t* c) { return modbus_write_bit(c, int(p.first), raw ? 1 : 0); });
  } else if (p.coils) {
    std::vector<uint8_t> bits(p.count);
    for (uint32_t b = 0; b < p.count; ++b) bits[b] = (raw >> b) & 1;
    transact(what, [&](modbus_t* c) { return modbus_write_bits(c, int(p.first), int(p.count), bits.data()); });
  } else if (p.count == 1) {
    transact(what, [&](modbus_t* c) { return modbus_write_register(c, int(p.first), uint16_t(raw)); });
  } else {
    const uint16_t regs[2] = {uint16_t(raw & 0xFFFF), uint16_t(raw >> 16)};
    transact(what, [&](modbus_t* c) { return modbus_write_registers(c, int(p.first), 2, regs); });
  }
}

}  // namespace hardware
}  // namespace plc_cell
