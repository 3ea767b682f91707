#pragma once
// The 10,000-instruction ladder of bench_scan (scan_bench.cpp): its fixed-seed generator,
// its IL text, and the same ladder compiled to straight-line C++ (the baseline). Included
// by scan_bench.cpp only.
#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>

// ---- the ladder, as data ----------------------------------------------------

namespace ladder {

enum class Op : uint8_t {
  Org, OrgNot, Ld, LdNot, And, AndNot, Or, OrNot, OrLd,  // contacts
  Out, Set, Rst,                                          // coils
  Tmr,                                                    // a = timer, b = preset
  Mov,   // FUN 8:  R[b] = R[a]
  MovK,  // FUN 8:  R[b] = a (constant)
  Add,   // FUN 11: R[c] = R[a] + b (constant)
  End,
};
enum class Dev : uint8_t { None, X, Y, M, T };

struct Ins {
  Op op = Op::End;
  Dev dev = Dev::None;
  uint16_t a = 0, b = 0, c = 0;
};

constexpr std::size_t kTarget = 10000;  // instructions, END included
constexpr std::size_t kMaxNets = 2000;
constexpr uint16_t kInputs = 64;     // X0..X63 are wired
constexpr uint16_t kRelays = 1500;   // M0..M1499 (M1912+ are special relays)
constexpr uint16_t kRegisters = 1000;
constexpr uint16_t kAlwaysOn = 1925;  // M1925

struct Ladder {
  Ins code[kTarget]{};
  uint16_t net_start[kMaxNets + 1]{};
  std::size_t size = 0;
  std::size_t nets = 0;
  uint16_t timers = 0;  // T0..T(timers-1) are used, each by one TMR
};

// splitmix64: tiny, good enough, and usable in a constant expression.
struct Rng {
  uint64_t s;
  constexpr uint64_t next() {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }
  constexpr uint32_t below(uint32_t n) { return static_cast<uint32_t>(next() % n); }
  constexpr bool chance(uint32_t percent) { return below(100) < percent; }
};

constexpr void emit(Ladder& l, Op op, Dev dev = Dev::None, uint16_t a = 0, uint16_t b = 0, uint16_t c = 0) {
  l.code[l.size++] = Ins{op, dev, a, b, c};
}

// A contact operand: mostly inputs and internal relays, some outputs and timer contacts.
constexpr std::pair<Dev, uint16_t> contact(Ladder& l, Rng& r) {
  const uint32_t p = r.below(100);
  if (p < 30) return {Dev::X, uint16_t(r.below(kInputs))};
  if (p < 75) return {Dev::M, uint16_t(r.below(kRelays))};
  if (p < 90 || l.timers == 0) return {Dev::Y, uint16_t(r.below(256))};
  return {Dev::T, uint16_t(r.below(l.timers))};
}

constexpr void emit_contact(Ladder& l, Rng& r, Op plain, Op negated) {
  const auto c = contact(l, r);
  emit(l, r.chance(25) ? negated : plain, c.first, c.second);
}

constexpr void emit_coil(Ladder& l, Rng& r) {
  const uint32_t p = r.below(100);
  const Op op = p < 70 ? Op::Out : p < 85 ? Op::Set : Op::Rst;
  if (r.chance(30)) emit(l, op, Dev::Y, uint16_t(r.below(256)));
  else emit(l, op, Dev::M, uint16_t(r.below(kRelays)));
}

// One network. Shapes and proportions follow typical machine ladders: mostly
// 3-5 contact rungs driving coils, a timer every tenth rung, some register moves.
constexpr void network(Ladder& l, Rng& r) {
  l.net_start[l.nets++] = uint16_t(l.size);
  if (l.nets % 10 == 0 && l.timers < 200) {
    emit_contact(l, r, Op::Org, Op::OrgNot);
    emit_contact(l, r, Op::And, Op::AndNot);
    const uint16_t t = l.timers++;
    // Presets of 50-500 ms (T0-49, 10 ms base) or 0.2-1 s (T50-199, 100 ms base):
    // with 1 ms scans the timers really run out during the benchmark.
    const uint16_t preset = t < 50 ? uint16_t(5 + r.below(46)) : uint16_t(2 + r.below(9));
    emit(l, Op::Tmr, Dev::T, t, preset);
    return;
  }
  if (r.chance(12)) {
    if (r.chance(40)) emit(l, Op::Org, Dev::M, kAlwaysOn);
    else emit_contact(l, r, Op::Org, Op::OrgNot);
    const uint32_t moves = 1 + r.below(2);
    for (uint32_t k = 0; k < moves; ++k) {
      const uint32_t p = r.below(100);
      const uint16_t d = uint16_t(r.below(kRegisters));
      if (p < 50) emit(l, Op::Mov, Dev::None, uint16_t(r.below(kRegisters)), d);
      else if (p < 65) emit(l, Op::MovK, Dev::None, uint16_t(r.below(1000)), d);
      else emit(l, Op::Add, Dev::None, uint16_t(r.below(kRegisters)), uint16_t(1 + r.below(100)), d);
    }
    return;
  }
  emit_contact(l, r, Op::Org, Op::OrgNot);
  const uint32_t n = 2 + r.below(3);
  for (uint32_t k = 0; k < n; ++k) {
    if (r.chance(60)) emit_contact(l, r, Op::And, Op::AndNot);
    else emit_contact(l, r, Op::Or, Op::OrNot);
  }
  if (r.chance(15)) {  // a parallel branch: LD ... AND ... ORLD
    emit_contact(l, r, Op::Ld, Op::LdNot);
    emit_contact(l, r, Op::And, Op::AndNot);
    emit(l, Op::OrLd);
  }
  emit_coil(l, r);
  if (r.chance(25)) emit_coil(l, r);
}

constexpr Ladder generate(uint64_t seed) {
  Ladder l{};
  Rng r{seed};
  // A network is at most 10 instructions; stop with 11..20 left so that one
  // AND-chain filler network makes the total exactly kTarget with END.
  while (l.size < kTarget - 1 - 20) network(l, r);
  l.net_start[l.nets++] = uint16_t(l.size);
  const std::size_t filler = kTarget - 1 - l.size;
  emit(l, Op::Org, Dev::M, kAlwaysOn);
  for (std::size_t k = 0; k + 2 < filler; ++k) emit_contact(l, r, Op::And, Op::AndNot);
  emit(l, Op::Out, Dev::M, uint16_t(r.below(kRelays)));
  emit(l, Op::End);
  l.net_start[l.nets] = uint16_t(l.size);
  return l;
}

constexpr Ladder kLadder = generate(0x5eed2024u);
static_assert(kLadder.size == kTarget, "the generated ladder must have exactly 10,000 instructions");

// ---- the ladder, as IL text -------------------------------------------------

inline std::string dev_name(Dev d, uint16_t i) {
  static const char* const names[] = {"", "X", "Y", "M", "T"};
  return names[static_cast<int>(d)] + std::to_string(i);
}

inline std::string to_il(const Ladder& l) {
  std::string s;
  s.reserve(l.size * 20);
  std::size_t net = 0;
  for (std::size_t i = 0; i < l.size; ++i) {
    if (net < l.nets && l.net_start[net] == i) s += "; network " + std::to_string(net++) + "\n";
    const Ins& in = l.code[i];
    const std::string d = dev_name(in.dev, in.a);
    switch (in.op) {
      case Op::Org: s += "ORG " + d; break;
      case Op::OrgNot: s += "ORG NOT " + d; break;
      case Op::Ld: s += "LD " + d; break;
      case Op::LdNot: s += "LD NOT " + d; break;
      case Op::And: s += "AND " + d; break;
      case Op::AndNot: s += "AND NOT " + d; break;
      case Op::Or: s += "OR " + d; break;
      case Op::OrNot: s += "OR NOT " + d; break;
      case Op::OrLd: s += "ORLD"; break;
      case Op::Out: s += "OUT " + d; break;
      case Op::Set: s += "SET " + d; break;
      case Op::Rst: s += "RST " + d; break;
      case Op::Tmr: s += "TMR T" + std::to_string(in.a) + " " + std::to_string(in.b); break;
      case Op::Mov: s += "FUN 8 S=R" + std::to_string(in.a) + " D=R" + std::to_string(in.b); break;
      case Op::MovK: s += "FUN 8 S=K" + std::to_string(in.a) + " D=R" + std::to_string(in.b); break;
      case Op::Add:
        s += "FUN 11 Sa=R" + std::to_string(in.a) + " Sb=K" + std::to_string(in.b) + " D=R" + std::to_string(in.c);
        break;
      case Op::End: s += "END"; break;
    }
    s += '\n';
  }
  return s;
}

// ---- the ladder, compiled: the hand-written C++ ideal --------------------------
//
// Each IL instruction becomes one inline statement with its address fixed at
// compile time, over plain one-byte-per-bit arrays -- what a programmer writing
// the networks by hand in C++ (or a ladder-to-C compiler) would produce. The
// LD stack is never deeper than one here, so one local holds it.

struct Image {
  bool X[256];
  bool Y[256];
  bool M[2048];
  bool T[256];
  uint16_t RT[256];
  uint16_t R[kRegisters];
  uint64_t rem_us[256];  // timer time not yet counted in RT
  bool running[256];
};

template <Dev D>
inline bool* bits(Image& m) {
  if constexpr (D == Dev::X) return m.X;
  else if constexpr (D == Dev::Y) return m.Y;
  else if constexpr (D == Dev::M) return m.M;
  else return m.T;
}

// The rung state a compiled program keeps in registers: the accumulator and the one-deep LD stack.
struct Rung {
  bool acc = false;
  bool saved = false;
};

template <std::size_t I>
__attribute__((always_inline)) inline void step(Image& m, Rung& r, uint32_t dt_us) {
  bool& acc = r.acc;
  bool& saved = r.saved;
  constexpr Ins in = kLadder.code[I];
  if constexpr (in.op == Op::Org) acc = bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::OrgNot) acc = !bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::Ld) { saved = acc; acc = bits<in.dev>(m)[in.a]; }
  else if constexpr (in.op == Op::LdNot) { saved = acc; acc = !bits<in.dev>(m)[in.a]; }
  else if constexpr (in.op == Op::And) acc = acc & bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::AndNot) acc = acc & !bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::Or) acc = acc | bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::OrNot) acc = acc | !bits<in.dev>(m)[in.a];
  else if constexpr (in.op == Op::OrLd) acc = saved | acc;
  else if constexpr (in.op == Op::Out) bits<in.dev>(m)[in.a] = acc;
  else if constexpr (in.op == Op::Set) { if (acc) bits<in.dev>(m)[in.a] = true; }
  else if constexpr (in.op == Op::Rst) { if (acc) bits<in.dev>(m)[in.a] = false; }
  else if constexpr (in.op == Op::Tmr) {
    // Same semantics as the interpreter: count whole time-base ticks, saturate at the preset.
    constexpr uint16_t n = in.a;
    constexpr int64_t preset = in.b;
    constexpr uint64_t base = n < 50 ? 10000 : n < 200 ? 100000 : 1000000;
    if (acc) {
      if (!m.running[n]) {
        m.running[n] = true;
        m.rem_us[n] = 0;
        m.RT[n] = 0;
      } else {
        m.rem_us[n] += dt_us;
        const uint64_t inc = m.rem_us[n] / base;
        m.rem_us[n] %= base;
        m.RT[n] = static_cast<uint16_t>(std::min<int64_t>(preset, int64_t(m.RT[n]) + int64_t(inc)));
      }
      m.T[n] = m.RT[n] >= preset;
    } else {
      m.running[n] = false;
      m.rem_us[n] = 0;
      m.RT[n] = 0;
      m.T[n] = false;
    }
  }
  else if constexpr (in.op == Op::Mov) { if (acc) m.R[in.b] = m.R[in.a]; }
  else if constexpr (in.op == Op::MovK) { if (acc) m.R[in.b] = in.a; }
  else if constexpr (in.op == Op::Add) { if (acc) m.R[in.c] = static_cast<uint16_t>(m.R[in.a] + in.b); }
}

// The program is compiled in chunks of 100 instructions, one function each:
// GCC's time grows quadratically with the length of one fold expression and
// with the size of one function, and a call per 100 instructions costs nothing
// measurable. The rung state is passed by value so that it stays in registers
// (a bool& could alias the bool arrays and force a reload after every coil).
constexpr std::size_t kChunk = 100;
static_assert(kTarget % kChunk == 0, "chunks must tile the program");

template <std::size_t B, std::size_t... J>
__attribute__((noinline)) Rung run_chunk(Image& m, Rung r, uint32_t dt_us, std::index_sequence<J...>) {
  (step<B + J>(m, r, dt_us), ...);  // END (the last instruction) compiles to nothing
  return r;
}

template <std::size_t... C>
void run_chunks(Image& m, uint32_t dt_us, std::index_sequence<C...>) {
  Rung r;
  ((r = run_chunk<C * kChunk>(m, r, dt_us, std::make_index_sequence<kChunk>{})), ...);
}

// One call per scan, like calling a compiled program.
__attribute__((noinline)) inline void run_compiled(Image& m, uint32_t dt_us) {
  run_chunks(m, dt_us, std::make_index_sequence<kTarget / kChunk>{});
}

}  // namespace ladder
