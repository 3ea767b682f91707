#include "plc_cell/core/interpreter.h"

#include <algorithm>

#include "plc_cell/core/error.h"

namespace plc_cell {

// ---- operand access ---------------------------------------------------------

static uint32_t pack_bits(const uint8_t* b, int n) {
  uint32_t v = 0;
  for (int k = 0; k < n; ++k) v |= uint32_t(b[k] & kBitState) << k;
  return v;
}

static void unpack_bits(uint8_t* b, int n, uint32_t v) {
  for (int k = 0; k < n; ++k)
    if (!(b[k] & kBitDisabled)) b[k] = (v >> k) & 1u;
}

uint32_t ExecContext::get_raw(const BoundOperand& o) const {
  switch (o.kind) {
    case Operand::Kind::Const: return static_cast<uint32_t>(o.k) & (is32 ? 0xFFFFFFFFu : 0xFFFFu);
    case Operand::Kind::Reg16: return o.w[0];
    case Operand::Kind::Reg32: return uint32_t(o.w[0]) | (uint32_t(o.w[1]) << 16);
    case Operand::Kind::Bits16: return pack_bits(o.b, 16);
    case Operand::Kind::Bits32: return pack_bits(o.b, 32);
    case Operand::Kind::Bit: return o.b[0] & kBitState;
  }
  return 0;
}

int64_t ExecContext::get(const BoundOperand& o) const {
  switch (o.kind) {
    case Operand::Kind::Const: return o.k;
    case Operand::Kind::Reg16:
    case Operand::Kind::Bits16: return static_cast<int16_t>(get_raw(o));
    case Operand::Kind::Reg32:
    case Operand::Kind::Bits32: return static_cast<int32_t>(get_raw(o));
    case Operand::Kind::Bit: return get_raw(o);
  }
  return 0;
}

void ExecContext::put(const BoundOperand& o, int64_t v) const {
  const uint32_t u = static_cast<uint32_t>(v);
  switch (o.kind) {
    case Operand::Kind::Const: break;  // the parser rejects constants as destinations
    case Operand::Kind::Reg16: o.w[0] = static_cast<uint16_t>(u); break;
    case Operand::Kind::Reg32:
      o.w[0] = static_cast<uint16_t>(u);
      o.w[1] = static_cast<uint16_t>(u >> 16);
      break;
    case Operand::Kind::Bits16: unpack_bits(o.b, 16, u); break;
    case Operand::Kind::Bits32: unpack_bits(o.b, 32, u); break;
    case Operand::Kind::Bit:
      if (!(o.b[0] & kBitDisabled)) o.b[0] = u & 1u;
      break;
  }
}

void ExecContext::flag(const BoundOperand& o, bool v) const {
  if (o.present && o.b && !(o.b[0] & kBitDisabled)) o.b[0] = v ? kBitState : 0;
}

// ---- loading ----------------------------------------------------------------

Interpreter::Interpreter(Memory& mem, const FunctionTable& functions)
    : mem_(mem), functions_(functions) {
  for (uint32_t t = 0; t < 256; ++t) timer_base_us_[t] = t < 50 ? 10000 : t < 200 ? 100000 : 1000000;
}

static BoundOperand bind_operand(Memory& mem, const Operand& o) {
  BoundOperand b;
  b.kind = o.kind;
  b.k = o.k;
  b.addr = o.addr;
  b.present = o.present;
  b.text = o.text;
  if (!o.present || o.kind == Operand::Kind::Const) return b;
  if (is_discrete(o.addr.area)) {
    b.b = mem.bits(o.addr.area) + o.addr.index;
  } else {
    b.w = mem.words(o.addr.area) + Memory::word_index(o.addr.area, o.addr.index);
  }
  return b;
}

void Interpreter::load(const Program& program) {
  std::vector<Bound> code;
  std::vector<BoundOperand> ops;
  code.reserve(program.code.size() + 1);
  for (size_t i = 0; i < program.code.size(); ++i) {
    const Instruction& in = program.code[i];
    Bound b{};
    b.op = in.op;
    b.is32 = in.is32;
    b.pulse = in.pulse;
    b.n_inputs = 1;
    b.edge = i < program.edge_slot_of.size() ? program.edge_slot_of[i] : ~0u;
    b.target = in.target;
    switch (in.op) {
      case Op::Jmp:
      case Op::Call: b.target = program.labels.at(in.label); break;
      case Op::RstReg:
        b.index = static_cast<uint32_t>(ops.size());
        ops.push_back(bind_operand(mem_, in.operands.at(0)));
        break;
      case Op::Tmr:
      case Op::Ctr:
        b.index = in.addr.index;
        b.target = static_cast<uint32_t>(ops.size());
        ops.push_back(bind_operand(mem_, in.operands.at(0)));
        break;
      case Op::For:
        b.index = static_cast<uint32_t>(ops.size());
        ops.push_back(bind_operand(mem_, in.operands.at(0)));
        break;
      case Op::Fun: {
        b.fn = functions_.find(in.fun);
        if (!b.fn) throw Error("FUN " + std::to_string(in.fun) + " is not available");
        b.n_inputs = static_cast<uint8_t>(b.fn->inputs.size());
        b.index = static_cast<uint32_t>(ops.size());
        b.n_ops = static_cast<uint16_t>(in.operands.size());
        for (const auto& o : in.operands) ops.push_back(bind_operand(mem_, o));
        break;
      }
      default:
        if (in.op <= Op::Rst && in.op != Op::AndLd && in.op != Op::OrLd) {
          b.bit = mem_.bits(in.addr.area) + in.addr.index;
          if (in.op == Op::Rst && (in.addr.area == Area::T || in.addr.area == Area::C)) {
            b.target = in.addr.area == Area::T ? 1 : 2;  // RST of a timer or counter clears its value
            b.index = in.addr.index;
          }
        }
        break;
    }
    code.push_back(b);
  }
  Bound end{};
  end.op = Op::End;
  code.push_back(end);  // a routine that runs off the end stops here with a fault

  program_ = program;
  code_ = std::move(code);
  ops_ = std::move(ops);
  reset_state();
}

void Interpreter::reset_state() {
  edges_.assign(program_.edge_slots, 0);
  timer_rem_us_.fill(0);
  timer_running_.fill(0);
  fault_.clear();
}

void Interpreter::set_fault(const Bound& b, const std::string& why) {
  const size_t pc = static_cast<size_t>(&b - code_.data());
  const int line = pc < program_.code.size() ? program_.code[pc].line : 0;
  fault_ = program_.file + ":" + std::to_string(line) + ": " + why;
}

bool Interpreter::run_main(uint64_t now_us, uint32_t dt_us, ScanEngine* engine) {
  if (code_.empty()) return true;
  return execute(0, now_us, dt_us, engine, false);
}

bool Interpreter::run_routine(const std::string& label, uint64_t now_us, ScanEngine* engine) {
  auto it = program_.labels.find(label);
  if (it == program_.labels.end()) {
    fault_ = "no routine labelled " + label;
    return false;
  }
  return execute(it->second + 1, now_us, 0, engine, true);
}

// ---- execution --------------------------------------------------------------

bool Interpreter::execute(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine,
                          bool routine) {
  bool acc = false;
  bool stack[kMaxStack];
  int sp = 0;
  uint32_t calls[kMaxCallDepth];
  int csp = 0;
  struct ForFrame {
    uint32_t body;
    int64_t remaining;
  } fors[kMaxForDepth * (kMaxCallDepth + 1)];
  int fsp = 0;
  uint64_t loops = 0;
  uint8_t* const t_bits = mem_.bits(Area::T);
  uint8_t* const c_bits = mem_.bits(Area::C);
  uint16_t* const rt = mem_.words(Area::RT);
  uint16_t* const rc = mem_.words(Area::RC);
  uint8_t* const edges = edges_.data();
  const Bound* const code = code_.data();
  ExecContext ctx(mem_);
  ctx.engine = engine;
  ctx.now_us = now_us;
  ctx.dt_us = dt_us;

  auto coil = [](uint8_t& c, bool v) {
    if (!(c & kBitDisabled)) c = v ? kBitState : 0;
  };
  auto edge_up = [&](const Bound& b, bool v) {
    uint8_t& e = edges[b.edge];
    const bool r = v && !e;
    e = v;
    return r;
  };
  auto edge_down = [&](const Bound& b, bool v) {
    uint8_t& e = edges[b.edge];
    const bool r = !v && e;
    e = v;
    return r;
  };

  for (;;) {
    const Bound& b = code[pc];
    switch (b.op) {
      case Op::Org: sp = 0; acc = *b.bit & kBitState; break;
      case Op::OrgNot: sp = 0; acc = !(*b.bit & kBitState); break;
      case Op::Ld: stack[sp++] = acc; acc = *b.bit & kBitState; break;
      case Op::LdNot: stack[sp++] = acc; acc = !(*b.bit & kBitState); break;
      case Op::And: acc = acc && (*b.bit & kBitState); break;
      case Op::AndNot: acc = acc && !(*b.bit & kBitState); break;
      case Op::Or: acc = acc || (*b.bit & kBitState); break;
      case Op::OrNot: acc = acc || !(*b.bit & kBitState); break;
      case Op::OrgUp: sp = 0; acc = edge_up(b, *b.bit & kBitState); break;
      case Op::OrgDown: sp = 0; acc = edge_down(b, *b.bit & kBitState); break;
      case Op::LdUp: stack[sp++] = acc; acc = edge_up(b, *b.bit & kBitState); break;
      case Op::LdDown: stack[sp++] = acc; acc = edge_down(b, *b.bit & kBitState); break;
      case Op::AndUp: { const bool e = edge_up(b, *b.bit & kBitState); acc = acc && e; break; }
      case Op::AndDown: { const bool e = edge_down(b, *b.bit & kBitState); acc = acc && e; break; }
      case Op::OrUp: { const bool e = edge_up(b, *b.bit & kBitState); acc = acc || e; break; }
      case Op::OrDown: { const bool e = edge_down(b, *b.bit & kBitState); acc = acc || e; break; }
      case Op::AndLd: acc = stack[--sp] && acc; break;
      case Op::OrLd: acc = stack[--sp] || acc; break;
      case Op::Out: coil(*b.bit, acc); break;
      case Op::OutNot: coil(*b.bit, !acc); break;
      case Op::Set: if (acc) coil(*b.bit, true); break;
      case Op::Rst:
        if (acc) {
          coil(*b.bit, false);
          if (b.target != 0) {
            if (b.target == 1) {
              rt[b.index] = 0;
              timer_rem_us_[b.index] = 0;
            } else {
              uint16_t* w = rc + rc_word_index(b.index);
              w[0] = 0;
              if (b.index >= kFirst32BitCounter) w[1] = 0;
            }
          }
        }
        break;
      case Op::RstReg:
        if (acc) {
          ctx.is32 = b.is32;
          ctx.put(ops_[b.index], 0);
        }
        break;
      case Op::Tmr: {
        const uint32_t n = b.index;
        ctx.is32 = false;
        const int64_t preset = ctx.get(ops_[b.target]);
        if (acc) {
          if (!timer_running_[n]) {
            timer_running_[n] = 1;
            timer_rem_us_[n] = 0;
            rt[n] = 0;
          } else {
            const uint64_t base = timer_base_us_[n];
            timer_rem_us_[n] += dt_us;
            const uint64_t inc = timer_rem_us_[n] / base;
            timer_rem_us_[n] %= base;
            const int64_t limit = std::max<int64_t>(preset, 0);
            rt[n] = static_cast<uint16_t>(std::min<int64_t>(limit, int64_t(rt[n]) + int64_t(inc)));
          }
          coil(t_bits[n], int64_t(rt[n]) >= preset);
        } else {
          timer_running_[n] = 0;
          timer_rem_us_[n] = 0;
          rt[n] = 0;
          coil(t_bits[n], false);
        }
        break;
      }
      case Op::Ctr: {
        const uint32_t n = b.index;
        const bool wide = n >= kFirst32BitCounter;
        ctx.is32 = wide;
        const int64_t preset = ctx.get(ops_[b.target]);
        uint16_t* w = rc + rc_word_index(n);
        int64_t v = wide ? int64_t(int32_t(uint32_t(w[0]) | (uint32_t(w[1]) << 16))) : int64_t(w[0]);
        if (edge_up(b, acc) && v < preset) {
          ++v;
          w[0] = static_cast<uint16_t>(v);
          if (wide) w[1] = static_cast<uint16_t>(uint64_t(v) >> 16);
        }
        coil(c_bits[n], v >= preset);
        break;
      }
      case Op::Fun: {
        const int n = b.n_inputs;
        ctx.inputs[n - 1] = acc;
        for (int k = n - 2; k >= 0; --k) ctx.inputs[k] = stack[--sp];
        bool en = ctx.inputs[0];
        acc = en;
        if (b.pulse) en = edge_up(b, en);
        if (en || b.fn->always_runs) {
          ctx.en = en;
          ctx.is32 = b.is32;
          ctx.instance = pc;
          b.fn->handler(ctx, ops_.data() + b.index);
        }
        break;
      }
      case Op::Lbl: break;
      case Op::Jmp:
        if (acc) {
          if (b.target <= pc && ++loops > loop_budget_) {
            set_fault(b, "watchdog: more than " + std::to_string(loop_budget_) +
                             " backward jumps in one scan");
            return false;
          }
          pc = b.target;
          continue;
        }
        break;
      case Op::Call:
        if (acc) {
          if (csp == kMaxCallDepth) {
            set_fault(b, "CALL nested deeper than " + std::to_string(kMaxCallDepth));
            return false;
          }
          calls[csp++] = pc + 1;
          pc = b.target + 1;
          continue;
        }
        break;
      case Op::Rts:
      case Op::Rti:
        if (csp == 0) {
          if (routine) return true;
          set_fault(b, b.op == Op::Rts ? "RTS without CALL" : "RTI outside an interrupt");
          return false;
        }
        pc = calls[--csp];
        continue;
      case Op::For: {
        if (fsp == static_cast<int>(sizeof fors / sizeof fors[0])) {
          set_fault(b, "FOR nested too deeply");
          return false;
        }
        ctx.is32 = false;
        const int64_t count = ctx.get(ops_[b.index]);
        if (count <= 0) {
          pc = b.target + 1;  // skip the body
          continue;
        }
        fors[fsp++] = {pc + 1, count};
        break;
      }
      case Op::Next:
        if (fsp > 0 && --fors[fsp - 1].remaining > 0) {
          if (++loops > loop_budget_) {
            set_fault(b, "watchdog: more than " + std::to_string(loop_budget_) +
                             " loop iterations in one scan");
            return false;
          }
          pc = fors[fsp - 1].body;
          continue;
        }
        if (fsp > 0) --fsp;
        break;
      case Op::End:
        if (!routine) return true;
        set_fault(b, "routine reached END without RTS/RTI");
        return false;
    }
    ++pc;
  }
}

}  // namespace plc_cell
