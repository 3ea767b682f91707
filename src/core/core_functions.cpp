// The core FUN instructions, numbered as on the FBs-PLC.
#include <cstdint>
#include <limits>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace {

using R = OperandRole;

int64_t lo(const ExecContext& c) { return c.is32 ? INT32_MIN : INT16_MIN; }
int64_t hi(const ExecContext& c) { return c.is32 ? INT32_MAX : INT16_MAX; }
uint64_t mask(const ExecContext& c) { return c.is32 ? 0xFFFFFFFFull : 0xFFFFull; }
int64_t wrap(const ExecContext& c, int64_t v) {
  return c.is32 ? int64_t(int32_t(uint32_t(v))) : int64_t(int16_t(uint16_t(v)));
}

// ADD/SUB: D = result wrapped to the width; CY on overflow above, BR below, ZR on zero.
void arith_result(ExecContext& c, const BoundOperand* o, int64_t r) {
  c.put(o[2], r);
  c.flag(o[3], wrap(c, r) == 0);
  c.flag(o[4], r > hi(c));
  c.flag(o[5], r < lo(c));
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

// FUN8/9: the moves.
void add_moves(FunctionTable& t) {
  FunctionSpec s;
  s.number = 8; s.mnemonic = "MOV";
  s.operands = {{"S", R::Source}, {"D", R::Dest}};
  s.handler = [](ExecContext& c, const BoundOperand* o) { c.put(o[1], c.get(o[0])); };
  t.add(s);

  s = {};
  s.number = 9; s.mnemonic = "MOVN";  // FBs "MOV/": move the complement
  s.operands = {{"S", R::Source}, {"D", R::Dest}};
  s.handler = [](ExecContext& c, const BoundOperand* o) { c.put(o[1], ~c.get_raw(o[0])); };
  t.add(s);
}

// FUN11-16: the arithmetic, in 16 or 32 bits (.D).
void add_arithmetic(FunctionTable& t) {
  FunctionSpec s;
  s.number = 11; s.mnemonic = "ADD";
  s.operands = abd_flags();
  s.handler = [](ExecContext& c, const BoundOperand* o) { arith_result(c, o, c.get(o[0]) + c.get(o[1])); };
  t.add(s);

  s = {};
  s.number = 12; s.mnemonic = "SUB";
  s.operands = abd_flags();
  s.handler = [](ExecContext& c, const BoundOperand* o) { arith_result(c, o, c.get(o[0]) - c.get(o[1])); };
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
    write_words(o[2], 2 * words, (uint64_t(q) & mask(c)) | ((uint64_t(r) & mask(c)) << (16 * words)));
    c.flag(o[3], wrap(c, q) == 0);
  };
  t.add(s);

  s = {};
  s.number = 15; s.mnemonic = "INC";
  s.operands = {{"D", R::Dest}, {"OVF", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t v = c.get(o[0]) + 1;
    c.put(o[0], v);
    c.flag(o[1], v > hi(c));
  };
  t.add(s);

  s = {};
  s.number = 16; s.mnemonic = "DEC";
  s.operands = {{"D", R::Dest}, {"UDF", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t v = c.get(o[0]) - 1;
    c.put(o[0], v);
    c.flag(o[1], v < lo(c));
  };
  t.add(s);
}

// FUN17 CMP and the word logic FUN18/19/35.
void add_compare_logic(FunctionTable& t) {
  FunctionSpec s;
  s.number = 17; s.mnemonic = "CMP";
  s.operands = {{"Sa", R::Source}, {"Sb", R::Source},
                {"EQ", R::BitOut, true}, {"GT", R::BitOut, true}, {"LT", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t a = c.get(o[0]), b = c.get(o[1]);
    c.flag(o[2], a == b);
    c.flag(o[3], a > b);
    c.flag(o[4], a < b);
  };
  t.add(s);

  struct Logic {
    uint16_t n;
    const char* m;
    int op;
  };
  for (const Logic& l : {Logic{18, "WAND", 0}, Logic{19, "WOR", 1}, Logic{35, "WXOR", 2}}) {
    s = {};
    s.number = l.n; s.mnemonic = l.m;
    s.operands = {{"Sa", R::Source}, {"Sb", R::Source}, {"D", R::Dest}, {"ZR", R::BitOut, true}};
    const int op = l.op;
    s.handler = [op](ExecContext& c, const BoundOperand* o) {
      const uint32_t a = c.get_raw(o[0]), b = c.get_raw(o[1]);
      const uint32_t r = op == 0 ? (a & b) : op == 1 ? (a | b) : (a ^ b);
      c.put(o[2], r);
      c.flag(o[3], (r & mask(c)) == 0);
    };
    t.add(s);
  }
}

// FUN20/21: the BCD conversions.
void add_conversions(FunctionTable& t) {
  FunctionSpec s;
  s.number = 20; s.mnemonic = "BCD";  // FBs "->BCD"
  s.operands = {{"S", R::Source}, {"D", R::Dest}, {"ERR", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int64_t v = c.get(o[0]);
    const int64_t max = c.is32 ? 99999999 : 9999;
    if (v < 0 || v > max) {
      c.flag(o[2], true);
      return;
    }
    c.flag(o[2], false);
    c.put(o[1], static_cast<int64_t>(to_bcd(static_cast<uint64_t>(v))));
  };
  t.add(s);

  s = {};
  s.number = 21; s.mnemonic = "BIN";  // FBs "->BIN"
  s.operands = {{"S", R::Source}, {"D", R::Dest}, {"ERR", R::BitOut, true}};
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    uint64_t v;
    if (!from_bcd(c.get_raw(o[0]), c.is32 ? 8 : 4, &v)) {
      c.flag(o[2], true);
      return;
    }
    c.flag(o[2], false);
    c.put(o[1], static_cast<int64_t>(v));
  };
  t.add(s);
}

// FUN51/52: the shifts.
void add_shifts(FunctionTable& t) {
  FunctionSpec s;
  for (int dir = 0; dir < 2; ++dir) {
    s = {};
    s.number = dir == 0 ? 51 : 52;
    s.mnemonic = dir == 0 ? "SHL" : "SHR";  // FBs SHFL / SHFR
    s.operands = {{"D", R::Dest}, {"N", R::Source}, {"OTB", R::BitOut, true}};
    s.handler = [dir](ExecContext& c, const BoundOperand* o) {
      const int width = c.is32 ? 32 : 16;
      const int64_t n = c.get(o[1]);
      if (n <= 0) return;
      const uint64_t v = c.get_raw(o[0]);
      uint64_t r;
      bool out;
      if (n > width) {
        r = 0;
        out = false;
      } else if (dir == 0) {
        out = (v >> (width - n)) & 1u;
        r = (v << n) & mask(c);
      } else {
        out = (v >> (n - 1)) & 1u;
        r = v >> n;
      }
      c.put(o[0], static_cast<int64_t>(r));
      c.flag(o[2], out);
    };
    t.add(s);
  }
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
