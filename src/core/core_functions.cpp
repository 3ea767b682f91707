// The core FUN instructions, numbered as on the FBs-PLC.
#include <cstdint>
#include <limits>
#include <vector>

#include "plc_cell/core/fun_forms.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace {

using R = OperandRole;

int64_t lo(bool is32) { return is32 ? INT32_MIN : INT16_MIN; }
int64_t hi(bool is32) { return is32 ? INT32_MAX : INT16_MAX; }
uint64_t mask(bool is32) { return is32 ? 0xFFFFFFFFull : 0xFFFFull; }
int64_t wrap(bool is32, int64_t v) {
  return is32 ? int64_t(int32_t(uint32_t(v))) : int64_t(int16_t(uint16_t(v)));
}

// ADD/SUB: D = result wrapped to the width; CY on overflow above, BR below, ZR on zero.
template <class O>
void arith_result(const O& o, int64_t r) {
  o.put(2, r);
  o.flag(3, wrap(o.is32(), r) == 0);
  o.flag(4, r > hi(o.is32()));
  o.flag(5, r < lo(o.is32()));
}

void write_words(const BoundOperand& d, int words, uint64_t v) {
  // MUL/DIV results span consecutive words starting at D (checked by the parser).
  if (d.w) {
    for (int k = 0; k < words; ++k) d.w[k] = static_cast<uint16_t>(v >> (16 * k));
  } else if (d.b) {
    for (int k = 0; k < 16 * words; ++k)
      if (!(d.b[k] & kBitDisabled)) d.b[k] = (v >> k) & 1u;
  }
}

uint64_t to_bcd(uint64_t v) {
  uint64_t r = 0;
  for (int s = 0; v; s += 4, v /= 10) r |= (v % 10) << s;
  return r;
}

bool from_bcd(uint64_t v, int digits, uint64_t* out) {
  uint64_t r = 0, scale = 1;
  for (int k = 0; k < digits; ++k, v >>= 4, scale *= 10) {
    const uint64_t d = v & 0xF;
    if (d > 9) return false;
    r += d * scale;
  }
  *out = r;
  return true;
}

std::vector<OperandSpec> abd_flags() {
  return {{"Sa", R::Source}, {"Sb", R::Source}, {"D", R::Dest},
          {"ZR", R::BitOut, true}, {"CY", R::BitOut, true}, {"BR", R::BitOut, true}};
}

// The bodies of the FUNs that have word forms (core/fun_forms.h): o is their operands.
struct Mov {
  template <class O> static void run(const O& o) { o.put(1, o.get(0)); }
};
struct MovNot {
  template <class O> static void run(const O& o) { o.put(1, ~o.get_raw(0)); }
};
template <int Sign>  // ADD (+1), SUB (-1)
struct AddSub {
  template <class O> static void run(const O& o) { arith_result(o, o.get(0) + Sign * o.get(1)); }
};
template <int Step>  // INC (+1: OVF above the range), DEC (-1: UDF below it)
struct IncDec {
  template <class O> static void run(const O& o) {
    const int64_t v = o.get(0) + Step;
    o.put(0, v);
    o.flag(1, Step > 0 ? v > hi(o.is32()) : v < lo(o.is32()));
  }
};
struct Cmp {
  template <class O> static void run(const O& o) {
    const int64_t a = o.get(0), b = o.get(1);
    o.flag(2, a == b);
    o.flag(3, a > b);
    o.flag(4, a < b);
  }
};
template <int Which>  // WAND (0), WOR (1), WXOR (2)
struct Logic {
  template <class O> static void run(const O& o) {
    const uint32_t a = o.get_raw(0), b = o.get_raw(1);
    const uint32_t r = Which == 0 ? (a & b) : Which == 1 ? (a | b) : (a ^ b);
    o.put(2, r);
    o.flag(3, (r & mask(o.is32())) == 0);
  }
};

// FUN8/9: the moves.
void add_moves(FunctionTable& t) {
  FunctionSpec s;
  s.number = 8; s.mnemonic = "MOV";
  s.operands = {{"S", R::Source}, {"D", R::Dest}};
  set_body<Mov>(s);
  t.add(s);

  s = {};
  s.number = 9; s.mnemonic = "MOVN";  // FBs "MOV/": move the complement
  s.operands = {{"S", R::Source}, {"D", R::Dest}};
  set_body<MovNot>(s);
  t.add(s);
}

// FUN11-16: the arithmetic, in 16 or 32 bits (.D).
void add_arithmetic(FunctionTable& t) {
  FunctionSpec s;
  s.number = 11; s.mnemonic = "ADD";
  s.operands = abd_flags();
  set_body<AddSub<1>>(s);
  t.add(s);

  s = {};
  s.number = 12; s.mnemonic = "SUB";
  s.operands = abd_flags();
  set_body<AddSub<-1>>(s);
  t.add(s);

  s = {};
  s.number = 13; s.mnemonic = "MUL";
  s.operands = {{"Sa", R::Source}, {"Sb", R::Source}, {"D", R::Dest, false, 2}, {"ZR", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t a = c.get(o[0]), b = c.get(o[1]);
    // 16 x 16 -> 32 bits at D, D+1; 32 x 32 -> 64 bits at D..D+3 (low word first).
    const __int128 r = static_cast<__int128>(a) * b;
    write_words(o[2], c.is32 ? 4 : 2, static_cast<uint64_t>(r));
    c.flag(o[3], r == 0);
  };
  t.add(s);

  s = {};
  s.number = 14; s.mnemonic = "DIV";
  s.operands = {{"Sa", R::Source}, {"Sb", R::Source}, {"D", R::Dest, false, 2},
                {"ZR", R::BitOut, true}, {"ERR", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t a = c.get(o[0]), b = c.get(o[1]);
    if (b == 0) {  // D keeps its value; ERR tells the program
      c.flag(o[4], true);
      return;
    }
    c.flag(o[4], false);
    const int64_t q = a / b, r = a % b;  // quotient at D, remainder at D+1 (D+2 for .D)
    const int words = c.is32 ? 2 : 1;
    write_words(o[2], 2 * words, (uint64_t(q) & mask(c.is32)) | ((uint64_t(r) & mask(c.is32)) << (16 * words)));
    c.flag(o[3], wrap(c.is32, q) == 0);
  };
  t.add(s);

  s = {};
  s.number = 15; s.mnemonic = "INC";
  s.operands = {{"D", R::Dest}, {"OVF", R::BitOut, true}};
  set_body<IncDec<1>>(s);
  t.add(s);

  s = {};
  s.number = 16; s.mnemonic = "DEC";
  s.operands = {{"D", R::Dest}, {"UDF", R::BitOut, true}};
  set_body<IncDec<-1>>(s);
  t.add(s);
}

// FUN17 CMP and the word logic FUN18/19/35.
void add_compare_logic(FunctionTable& t) {
  FunctionSpec s;
  s.number = 17; s.mnemonic = "CMP";
  s.operands = {{"Sa", R::Source}, {"Sb", R::Source},
                {"EQ", R::BitOut, true}, {"GT", R::BitOut, true}, {"LT", R::BitOut, true}};
  set_body<Cmp>(s);
  t.add(s);

  const std::vector<OperandSpec> operands = {{"Sa", R::Source}, {"Sb", R::Source}, {"D", R::Dest},
                                             {"ZR", R::BitOut, true}};
  s = {};
  s.number = 18; s.mnemonic = "WAND";
  s.operands = operands;
  set_body<Logic<0>>(s);
  t.add(s);
  s = {};
  s.number = 19; s.mnemonic = "WOR";
  s.operands = operands;
  set_body<Logic<1>>(s);
  t.add(s);
  s = {};
  s.number = 35; s.mnemonic = "WXOR";
  s.operands = operands;
  set_body<Logic<2>>(s);
  t.add(s);
}

// FUN20/21: the BCD conversions.
struct ToBcd {
  template <class O> static void run(const O& o) {
    const int64_t v = o.get(0);
    const int64_t max = o.is32() ? 99999999 : 9999;
    if (v < 0 || v > max) {
      o.flag(2, true);
      return;
    }
    o.flag(2, false);
    o.put(1, static_cast<int64_t>(to_bcd(static_cast<uint64_t>(v))));
  }
};
struct FromBcd {
  template <class O> static void run(const O& o) {
    uint64_t v;
    if (!from_bcd(o.get_raw(0), o.is32() ? 8 : 4, &v)) {
      o.flag(2, true);
      return;
    }
    o.flag(2, false);
    o.put(1, static_cast<int64_t>(v));
  }
};

void add_conversions(FunctionTable& t) {
  FunctionSpec s;
  s.number = 20; s.mnemonic = "BCD";  // FBs "->BCD"
  s.operands = {{"S", R::Source}, {"D", R::Dest}, {"ERR", R::BitOut, true}};
  set_body<ToBcd>(s);
  t.add(s);

  s = {};
  s.number = 21; s.mnemonic = "BIN";  // FBs "->BIN"
  s.operands = {{"S", R::Source}, {"D", R::Dest}, {"ERR", R::BitOut, true}};
  set_body<FromBcd>(s);
  t.add(s);
}

// FUN51/52: the shifts, left (Dir 0) and right (Dir 1); OTB takes the last bit out.
template <int Dir>
struct Shift {
  template <class O> static void run(const O& o) {
    const int width = o.is32() ? 32 : 16;
    const int64_t n = o.get(1);
    if (n <= 0) return;
    const uint64_t v = o.get_raw(0);
    uint64_t r;
    bool out;
    if (n > width) {
      r = 0;
      out = false;
    } else if (Dir == 0) {
      out = (v >> (width - n)) & 1u;
      r = (v << n) & mask(o.is32());
    } else {
      out = (v >> (n - 1)) & 1u;
      r = v >> n;
    }
    o.put(0, static_cast<int64_t>(r));
    o.flag(2, out);
  }
};

void add_shifts(FunctionTable& t) {
  FunctionSpec s;
  s.number = 51; s.mnemonic = "SHL";  // FBs SHFL
  s.operands = {{"D", R::Dest}, {"N", R::Source}, {"OTB", R::BitOut, true}};
  set_body<Shift<0>>(s);
  t.add(s);
  s = {};
  s.number = 52; s.mnemonic = "SHR";  // FBs SHFR
  s.operands = {{"D", R::Dest}, {"N", R::Source}, {"OTB", R::BitOut, true}};
  set_body<Shift<1>>(s);
  t.add(s);
}

}  // namespace

FunctionTable FunctionTable::with_core_functions() {
  FunctionTable t;
  add_moves(t);
  add_arithmetic(t);
  add_compare_logic(t);
  add_conversions(t);
  add_shifts(t);
  return t;
}

}  // namespace plc_cell
