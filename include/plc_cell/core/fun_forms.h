#pragma once
// One FUN body, two compiled forms (docs/native-engine.md, "FUN calls"). A body is a class
// with `template <class Ops> static void run(const Ops& o)` that reaches its operands only
// through o: get (signed), get_raw (bit pattern), put, flag, and is32(). It is compiled once
// over BoundOperands (any operand kind, through ExecContext: the FunctionSpec's handler)
// and once per width over WordOperands (bound pointers: the word forms). Both engines call
// the word form where an instruction's operands allow it and the handler elsewhere, so
// each instruction's semantics stay one source.
#include <cstdint>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {

// The handler's view: bound operands of every kind, read and written by ExecContext.
class BoundOperands {
 public:
  BoundOperands(const ExecContext& c, const BoundOperand* o) : c_(c), o_(o) {}
  bool is32() const { return c_.is32; }
  int64_t get(int i) const { return c_.get(o_[i]); }
  uint32_t get_raw(int i) const { return c_.get_raw(o_[i]); }
  void put(int i, int64_t v) const { c_.put(o_[i], v); }
  void flag(int i, bool v) const { c_.flag(o_[i], v); }

 private:
  const ExecContext& c_;
  const BoundOperand* o_;
};

// The word forms' view: operand i is p[i], a register's word (a constant's slot holds it as
// two words, low word first, as a Reg32), a discrete's byte, or null for an absent flag. Reads and writes are those of ExecContext on Reg16/Reg32, Const and Bit operands.
template <bool Wide>
class WordOperands {
 public:
  explicit WordOperands(void* const* p) : p_(p) {}
  static constexpr bool is32() { return Wide; }
  int64_t get(int i) const {
    return Wide ? int64_t(int32_t(get_raw(i))) : int64_t(int16_t(get_raw(i)));
  }
  uint32_t get_raw(int i) const {
    const uint16_t* w = static_cast<const uint16_t*>(p_[i]);
    return Wide ? uint32_t(w[0]) | (uint32_t(w[1]) << 16) : w[0];
  }
  void put(int i, int64_t v) const {
    uint16_t* w = static_cast<uint16_t*>(p_[i]);
    w[0] = static_cast<uint16_t>(v);
    if (Wide) w[1] = static_cast<uint16_t>(uint64_t(v) >> 16);
  }
  void flag(int i, bool v) const {
    uint8_t* b = static_cast<uint8_t*>(p_[i]);
    if (b && !(*b & kBitDisabled)) *b = v ? kBitState : 0;
  }

 private:
  void* const* p_;
};

template <class Body, bool Wide>
void word_form(void* o0, void* o1, void* o2, void* o3, void* o4, void* o5) noexcept {
  void* const p[6] = {o0, o1, o2, o3, o4, o5};
  Body::run(WordOperands<Wide>(p));
}

// Sets s's handler and its word forms from one body.
template <class Body>
void set_body(FunctionSpec& s) {
  s.handler = [](ExecContext& c, const BoundOperand* o) { Body::run(BoundOperands(c, o)); };
  s.words = WordForms{&word_form<Body, false>, &word_form<Body, true>};
}

}  // namespace plc_cell
