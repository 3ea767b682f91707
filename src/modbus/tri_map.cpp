#include "plc_cell/modbus/tri_map.h"

#include <string>
#include <vector>

#include "plc_cell/tri/memory_map.h"

namespace plc_cell {
namespace modbus {
namespace {

using tri::BitKind;

// One element of the map: a discrete, 16 discretes packed into a word (bit 0 = the
// lowest-numbered), or a register word (DATE[] converted to the TRi's form).
struct Element {
  enum Kind : uint8_t { Bit, Packed, Word } kind = Word;
  BitKind bits = BitKind::Input;  // Bit, Packed
  uint32_t n = 0;                 // Bit: the TRi number; Packed: the first TRi number
  Address reg;                    // Word
  uint32_t date = 0;              // Word: DATE[date] (1..4), 0 for none
};

struct BitRange {
  uint32_t first, count;
  BitKind kind;
};
// Table 14.1, bit addresses (Modicon n = wire n - 1): input n at n, output n at 256 + n,
// timer n at 512 + n, counter n at 768 + n, relay n at 1024 + n.
constexpr BitRange kBits[] = {{0, 256, BitKind::Input},    {256, 256, BitKind::Output}, {512, 64, BitKind::Timer},
                              {768, 64, BitKind::Counter}, {1024, 512, BitKind::Relay}};
// Word addresses of the packed I/O: INPUT[1..16] at 4-0001, OUTPUT[] at 4-0017, the
// timer and counter contacts at 4-0033 and 4-0049, RELAY[1..32] at 4-0065.
constexpr BitRange kPacked[] = {{0, 16, BitKind::Input},    {16, 16, BitKind::Output}, {32, 4, BitKind::Timer},
                                {48, 4, BitKind::Counter}, {64, 32, BitKind::Relay}};

bool resolve_bit(uint32_t addr, Element* e) {
  for (const auto& r : kBits)
    if (addr >= r.first && addr < r.first + r.count) {
      e->kind = Element::Bit;
      e->bits = r.kind;
      e->n = addr - r.first + 1;
      return true;
    }
  return false;
}

bool resolve_word(uint32_t addr, Element* e) {
  if (addr == 96) addr = 95;  // the table prints relays 497-512 at 4-0097; its progression gives 4-0096
  for (const auto& r : kPacked)
    if (addr >= r.first && addr < r.first + r.count) {
      e->kind = Element::Packed;
      e->bits = r.kind;
      e->n = 16 * (addr - r.first) + 1;
      return true;
    }
  e->kind = Element::Word;
  if (addr >= 128 && addr < 128 + tri::kTimers) return e->reg = tri::timer_pv(addr - 127), true;
  if (addr >= 256 && addr < 256 + tri::kCounters) return e->reg = tri::counter_pv(addr - 255), true;
  if (addr >= 512 && addr <= 514) return tri::time_register(addr - 511, &e->reg);
  if (addr >= 516 && addr <= 519) {
    e->date = addr - 515;
    return tri::date_register(e->date, &e->reg);
  }
  if (addr >= 714 && addr < 714 + 52) {  // A..Z: 4-0715/0716 .. 4-0765/0766, high word first
    const uint32_t k = (addr - 714) / 2;
    if (!tri::integer_var(k, &e->reg)) return false;
    e->reg.width = Width::Word;
    e->reg.index += (addr - 714) % 2 == 0 ? 1 : 0;
    return true;
  }
  if (addr >= 1000 && addr < 1000 + tri::kDmWords) return tri::dm(addr - 999, &e->reg);
  return false;
}

Address bit_of(const Element& e, uint32_t k) {
  Address a;
  tri::bit_address(e.bits, e.n + k, &a);
  return a;
}

bool may_write(const WritableRanges* w, const Element& e) {
  if (!w || w->everything()) return true;
  if (e.kind == Element::Word) return w->allows(e.reg.area, e.reg.index, 1);
  const uint32_t n = e.kind == Element::Packed ? 16 : 1;
  for (uint32_t k = 0; k < n; ++k) {
    const Address a = bit_of(e, k);
    if (!w->allows(a.area, a.index, 1)) return false;
  }
  return true;
}

void write_bit(ScanEngine& eng, Memory& m, const Address& a, bool v) {
  m.set_bit(a.area, a.index, v);
  // Writing an input plays the sensor, as every other server does.
  if (a.area == Area::X && !m.disabled(Area::X, a.index)) eng.set_input(a.index, v);
}

uint16_t read(const Memory& m, const Element& e) {
  switch (e.kind) {
    case Element::Bit: {
      const Address a = bit_of(e, 0);
      return m.bit(a.area, a.index);
    }
    case Element::Packed: {
      uint16_t w = 0;
      for (uint32_t k = 0; k < 16; ++k) {
        const Address a = bit_of(e, k);
        w = uint16_t(w | (m.bit(a.area, a.index) ? 1u << k : 0u));
      }
      return w;
    }
    case Element::Word: {
      const uint16_t v = uint16_t(m.read(e.reg));
      return e.date ? tri::date_from_fbs(e.date, v) : v;
    }
  }
  return 0;
}

void write(ScanEngine& eng, Memory& m, const Element& e, uint16_t v) {
  switch (e.kind) {
    case Element::Bit: write_bit(eng, m, bit_of(e, 0), v != 0); break;
    case Element::Packed:
      for (uint32_t k = 0; k < 16; ++k) write_bit(eng, m, bit_of(e, k), (v >> k) & 1u);
      break;
    case Element::Word: m.write(e.reg, e.date ? tri::date_to_fbs(e.date, v) : v); break;
  }
}

class TriMap : public MapProfile {
 public:
  const char* name() const override { return "tri"; }
  bool transfer(ScanEngine& eng, Memory& m, const Transfer& t, const WritableRanges* writable) const override {
    const bool bits = t.bits();
    auto resolve = [bits](uint32_t addr, Element* e) { return bits ? resolve_bit(addr, e) : resolve_word(addr, e); };
    std::vector<Element> wr(t.wr_count), rd(t.rd_count);
    for (uint32_t i = 0; i < t.wr_count; ++i)
      if (!resolve(t.wr_addr + i, &wr[i]) || !may_write(writable, wr[i])) return false;
    for (uint32_t i = 0; i < t.rd_count; ++i)
      if (!resolve(t.rd_addr + i, &rd[i])) return false;
    for (uint32_t i = 0; i < t.wr_count; ++i) write(eng, m, wr[i], bits ? t.wbits[i] : t.wwords[i]);
    for (uint32_t i = 0; i < t.rd_count; ++i) {
      const uint16_t v = read(m, rd[i]);
      if (bits) t.rbits[i] = uint8_t(v);
      else t.rwords[i] = v;
    }
    return true;
  }
};

}  // namespace

const MapProfile& tri_map_profile() {
  static const TriMap map;
  return map;
}

}  // namespace modbus
}  // namespace plc_cell
