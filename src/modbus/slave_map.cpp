#include "plc_cell/modbus/slave_map.h"

#include <cstring>
#include <iterator>

#include "plc_cell/core/memory.h"
#include "plc_cell/modbus/map_profile.h"

namespace plc_cell {
namespace modbus {

namespace {

struct Segment {
  uint32_t modbus_first;
  uint32_t count;
  Area area;
  uint32_t index;  // element (bits) or word-store index (registers)
};

// The manual's "Available Range" tables [M:5023-5076], as 0-based addresses (ref - 1).
constexpr Segment kDefaultCoils[] = {
    {0, 256, Area::Y, 0},    {1000, 256, Area::X, 0}, {2000, 2002, Area::M, 0},
    {6000, 1000, Area::S, 0}, {9000, 256, Area::T, 0}, {9500, 256, Area::C, 0},
};
constexpr Segment kDefaultRegisters[] = {
    {0, 4168, Area::R, 0},     {5000, 999, Area::R, 5000}, {6000, 2999, Area::D, 0},
    {9000, 256, Area::RT, 0},  {9500, kRcWordCount, Area::RC, 0},  // C200..C255: 2 words each
};

bool in(const Segment& s, uint32_t addr, uint32_t count, Run* out) {
  if (addr < s.modbus_first || uint64_t(addr) + count > uint64_t(s.modbus_first) + s.count) return false;
  out->area = s.area;
  out->index = s.index + (addr - s.modbus_first);
  return true;
}

template <size_t N>
bool in_any(const Segment (&segs)[N], uint32_t addr, uint32_t count, Run* out) {
  for (const auto& s : segs)
    if (in(s, addr, count, out)) return true;
  return false;
}

// One user group: Modbus start, FATEK start, count, checked against the manual's
// ranges (start 0..max_start, count 1..max_count, and the run inside the area).
bool user_group(const Memory& m, uint32_t reg, Area area, uint32_t max_start, uint32_t max_count,
                uint32_t addr, uint32_t count, Run* out) {
  const uint32_t mb = m.reg(Area::R, reg), first = m.reg(Area::R, reg + 1), n = m.reg(Area::R, reg + 2);
  if (first > max_start || n < 1 || n > max_count) return false;
  if (first + n > max_start + 1) return false;  // M0..M2001, R0..R3839
  return in(Segment{mb, n, area, first}, addr, count, out);
}

// Word-store index of RC back to the counter it belongs to (C200.. take two words).
uint32_t rc_counter(uint32_t w) { return w < kFirst32BitCounter ? w : kFirst32BitCounter + (w - kFirst32BitCounter) / 2; }

bool may_write(const WritableRanges* w, const Run& run, uint32_t count) {
  if (!w || w->everything()) return true;
  if (run.area != Area::RC) return w->allows(run.area, run.index, count);
  const uint32_t first = rc_counter(run.index), last = rc_counter(run.index + count - 1);
  return w->allows(Area::RC, first, last - first + 1);
}

// The FBs manual's map: the default tables, or the user map of R3968.. (read from PLC
// memory at each request). A request never spans two FBs areas, so it is one run.
class FbsMap : public MapProfile {
 public:
  const char* name() const override { return "fbs"; }
  bool transfer(ScanEngine&, Memory& m, const Transfer& t, const WritableRanges* writable) const override {
    Run rr, wr;
    if (t.rd_count && !resolve(m, t.table, t.rd_addr, t.rd_count, &rr)) return false;
    if (t.wr_count && !(resolve(m, t.table, t.wr_addr, t.wr_count, &wr) && may_write(writable, wr, t.wr_count)))
      return false;
    const bool bits = t.bits();
    if (t.wr_count) {
      if (bits) {
        for (uint32_t i = 0; i < t.wr_count; ++i)
          if (bool(t.wbits[i]) != m.bit(wr.area, wr.index + i)) m.set_bit(wr.area, wr.index + i, t.wbits[i] != 0);
      } else {
        uint16_t* w = m.words(wr.area) + wr.index;
        for (uint32_t i = 0; i < t.wr_count; ++i) w[i] = t.wwords[i];
      }
    }
    if (t.rd_count) {
      if (bits) {
        const uint8_t* src = m.bits(rr.area) + rr.index;
        for (uint32_t i = 0; i < t.rd_count; ++i) t.rbits[i] = src[i] & kBitState;
      } else {
        std::memcpy(t.rwords, m.words(rr.area) + rr.index, sizeof(uint16_t) * t.rd_count);
      }
    }
    return true;
  }
};

}  // namespace

const MapProfile& fbs_map_profile() {
  static const FbsMap map;
  return map;
}

bool user_map_enabled(const Memory& m) { return m.reg(Area::R, kUserMapRegister) == kUserMapMagic; }

bool resolve(const Memory& m, Table t, uint32_t addr, uint32_t count, Run* out) {
  if (count == 0) return false;
  const bool user = user_map_enabled(m);
  switch (t) {
    case Table::Coils:  // FC 01, 05, 15
      return user ? user_group(m, 3969, Area::M, 2001, 2001, addr, count, out)
                  : in_any(kDefaultCoils, addr, count, out);
    case Table::HoldingRegisters:  // FC 03, 06, 16, 23
      return user ? user_group(m, 3978, Area::R, 3839, 3840, addr, count, out)
                  : in_any(kDefaultRegisters, addr, count, out);
    // The manual says "Don't care R3968" for these two groups: they apply whenever
    // configured. Unconfigured (count 0), there is no 1x / 3x space.
    case Table::DiscreteInputs:  // FC 02
      return user_group(m, 3972, Area::M, 2001, 2001, addr, count, out);
    case Table::InputRegisters:  // FC 04
      return user_group(m, 3975, Area::R, 3839, 3840, addr, count, out);
  }
  return false;
}

}  // namespace modbus
}  // namespace plc_cell
