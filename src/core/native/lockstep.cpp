#include "plc_cell/core/native/lockstep.h"

#include <cstring>

namespace plc_cell {

namespace {

// Whether operand o (or an instruction's own address) covers element i of area a.
bool covers(const Address& at, Operand::Kind kind, Area a, uint32_t i) {
  if (at.area != a) return false;
  uint32_t n = 1;
  if (kind == Operand::Kind::Reg32) n = 2;
  if (kind == Operand::Kind::Bits16) n = 16;
  if (kind == Operand::Kind::Bits32) n = 32;
  return i >= at.index && i < at.index + n;
}

std::string writer_of(const Program& p, Area a, uint32_t i) {
  for (const Instruction& in : p.code) {
    bool hit = false;
    if (in.op >= Op::Out && in.op <= Op::Ctr) {
      hit = covers(in.addr, Operand::Kind::Bit, a, i);
      if ((in.op == Op::Tmr && a == Area::RT) || (in.op == Op::Ctr && a == Area::RC))
        hit = hit || in.addr.index == i;
    }
    for (const Operand& o : in.operands)
      hit = hit || (o.present && o.kind != Operand::Kind::Const && covers(o.addr, o.kind, a, i));
    if (hit) return p.file + ":" + std::to_string(in.line);
  }
  return "no instruction names it";
}

}  // namespace

std::string first_difference(const Memory& native, const Memory& interpreter, const Program& program,
                             const std::string& what) {
  for (int k = 0; k < kAreaCount; ++k) {
    const Area a = static_cast<Area>(k);
    const bool bits = is_discrete(a);
    const uint32_t n = bits ? area_size(a) : Memory::word_count(a);
    const void* p = bits ? static_cast<const void*>(native.bits(a)) : native.words(a);
    const void* q = bits ? static_cast<const void*>(interpreter.bits(a)) : interpreter.words(a);
    if (std::memcmp(p, q, bits ? n : n * sizeof(uint16_t)) == 0) continue;  // the usual case, fast
    for (uint32_t j = 0; j < n; ++j) {
      const uint32_t x = bits ? native.bits(a)[j] : native.words(a)[j];
      const uint32_t y = bits ? interpreter.bits(a)[j] : interpreter.words(a)[j];
      if (x == y) continue;
      // RC keeps its 32-bit counters as word pairs; name the element, not the word.
      const uint32_t element =
          a == Area::RC && j >= kFirst32BitCounter ? kFirst32BitCounter + (j - kFirst32BitCounter) / 2 : j;
      const Address at{a, bits ? Width::Bit : Width::Word, element};
      return "lockstep: " + format_address(at) + " is " + std::to_string(x) + " on the native engine and " +
             std::to_string(y) + " on the interpreter after " + what + " (written by " +
             writer_of(program, a, element) + ")";
    }
  }
  return {};
}

Lockstep::Lockstep(const FunctionTable& functions) : shadow_(memory_, functions) {}

void Lockstep::sync(const Memory& primary, const Interpreter& settings) {
  memory_ = primary;  // same sizes: the vectors keep their storage, so bound pointers stay valid
  for (uint32_t t = 0; t < 256; ++t) shadow_.set_timer_base(t, settings.timer_base(t));
}

bool Lockstep::run(const std::string& routine, uint64_t now_us, uint32_t dt_us) {
  return routine.empty() ? shadow_.run_main(now_us, dt_us, nullptr) : shadow_.run_routine(routine, now_us, nullptr);
}

}  // namespace plc_cell
