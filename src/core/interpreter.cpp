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
  run<false>(kInitDispatch, 0, 0, nullptr, false);
  run<true>(kInitDispatch, 0, 0, nullptr, false);
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
  std::vector<Extra> extras;
  std::vector<BoundOperand> ops;
  std::vector<int> extra_of(program.code.size(), -1);
  std::vector<Op> bound_op;
  code.reserve(program.code.size() + 1);
  bound_op.reserve(program.code.size() + 1);
  for (size_t i = 0; i < program.code.size(); ++i) {
    const Instruction& in = program.code[i];
    Bound b{};
    Op op = in.op;
    const uint32_t edge = i < program.edge_slot_of.size() ? program.edge_slot_of[i] : ~0u;
    Extra x{};
    x.edge = edge;
    x.is32 = in.is32;
    x.pulse = in.pulse;
    x.n_inputs = 1;
    x.first_op = static_cast<uint32_t>(ops.size());
    bool needs_extra = true;
    switch (in.op) {
      case Op::Jmp:
      case Op::Call:
        b.arg = program.labels.at(in.label);
        needs_extra = false;
        break;
      case Op::RstReg:
      case Op::For:
        x.number = in.target;
        ops.push_back(bind_operand(mem_, in.operands.at(0)));
        break;
      case Op::Tmr:
      case Op::Ctr:
        x.number = in.addr.index;
        ops.push_back(bind_operand(mem_, in.operands.at(0)));
        break;
      case Op::Fun:
        x.fn = functions_.find(in.fun);
        if (!x.fn) throw Error("FUN " + std::to_string(in.fun) + " is not available");
        x.n_inputs = static_cast<uint8_t>(x.fn->inputs.size());
        x.n_ops = static_cast<uint16_t>(in.operands.size());
        for (const auto& o : in.operands) ops.push_back(bind_operand(mem_, o));
        break;
      case Op::Rst:
        if (in.addr.area == Area::T || in.addr.area == Area::C) {
          x.clears = in.addr.area == Area::T ? 1 : 2;
          x.number = in.addr.index;
          op = Op::RstReg;  // a timer/counter reset runs the register path
          ops.push_back(BoundOperand{});
          ops.back().b = mem_.bits(in.addr.area) + in.addr.index;
          break;
        }
        [[fallthrough]];
      default:
        needs_extra = false;
        b.arg = edge;
        if (in.op <= Op::Rst && in.op != Op::AndLd && in.op != Op::OrLd)
          b.bit = mem_.bits(in.addr.area) + in.addr.index;
        break;
    }
    if (needs_extra) {
      extra_of[i] = static_cast<int>(extras.size());
      extras.push_back(x);
    }
    b.handler = handler_of_[static_cast<size_t>(op)];
    code.push_back(b);
    bound_op.push_back(op);
  }
  Bound end{};
  end.handler = handler_of_[static_cast<size_t>(Op::End)];
  code.push_back(end);  // a routine that runs off the end stops here with a fault
  bound_op.push_back(Op::End);
  for (size_t i = 0; i < extra_of.size(); ++i)
    if (extra_of[i] >= 0) code[i].extra = &extras[static_cast<size_t>(extra_of[i])];

  program_ = program;
  code_ = std::move(code);
  extras_ = std::move(extras);  // moving a vector keeps its elements where they are
  ops_ = std::move(ops);
  bound_op_ = std::move(bound_op);
  record_into(nullptr);  // a recording belongs to the program it was started on
  reset_state();
}

void Interpreter::record_into(uint8_t* seen) {
  seen_ = seen;
  if (!seen) {
    recorded_code_.clear();
    return;
  }
  recorded_code_ = code_;
  for (size_t i = 0; i < recorded_code_.size(); ++i)
    recorded_code_[i].handler = recording_handler_of_[static_cast<size_t>(bound_op_[i])];
}

void Interpreter::reset_state() {
  edges_.assign(program_.edge_slots, 0);
  timer_rem_us_.fill(0);
  timer_running_.fill(0);
  fault_.clear();
}

void Interpreter::set_fault(size_t pc, const std::string& why) {
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

bool Interpreter::execute(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine) {
  return seen_ ? run<true>(pc, now_us, dt_us, engine, routine) : run<false>(pc, now_us, dt_us, engine, routine);
}

// Threaded dispatch: every handler ends in its own indirect jump (GCC computed goto),
// which the CPU predicts per instruction kind pair, and contacts are branch-free.
// kRecord adds the coverage writes; each instantiation has its own handlers, so the
// instructions carry the offsets of one of them (code_ or recorded_code_).
template <bool kRecord>
bool Interpreter::run(uint32_t start, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine) {
  static void* const kDispatch[] = {
      &&op_org,      &&op_org_not, &&op_ld,      &&op_ld_not,   &&op_and,     &&op_and_not,
      &&op_or,       &&op_or_not,  &&op_org_up,  &&op_org_down, &&op_ld_up,   &&op_ld_down,
      &&op_and_up,   &&op_and_down, &&op_or_up,  &&op_or_down,  &&op_and_ld,  &&op_or_ld,
      &&op_out,      &&op_out_not, &&op_set,     &&op_rst,      &&op_rst_reg, &&op_tmr,
      &&op_ctr,      &&op_fun,     &&op_lbl,     &&op_jmp,      &&op_call,    &&op_rts,
      &&op_rti,      &&op_for,     &&op_next,    &&op_end};
  static_assert(sizeof kDispatch / sizeof kDispatch[0] == static_cast<size_t>(Op::End) + 1,
                "one handler per opcode");
  if (start == kInitDispatch) {  // load() stores each handler's offset in the instruction
    auto& handler_of = kRecord ? recording_handler_of_ : handler_of_;
    for (size_t i = 0; i < handler_of.size(); ++i)
      handler_of[i] = static_cast<int32_t>(static_cast<const char*>(kDispatch[i]) -
                                            static_cast<const char*>(&&op_org));
    return true;
  }

  unsigned acc = 0;
  uint8_t stack[kMaxStack];
  int sp = 0;
  const Bound* calls[kMaxCallDepth];
  int csp = 0;
  struct ForFrame {
    const Bound* body;
    int64_t remaining;
  } fors[kMaxForDepth * (kMaxCallDepth + 1)];
  int fsp = 0;
  uint64_t loops = 0;
  uint8_t* const t_bits = mem_.bits(Area::T);
  uint8_t* const c_bits = mem_.bits(Area::C);
  uint16_t* const rt = mem_.words(Area::RT);
  uint16_t* const rc = mem_.words(Area::RC);
  uint8_t* const edges = edges_.data();
  const Bound* const code = kRecord ? recorded_code_.data() : code_.data();
  uint8_t* const seen = seen_;
  const Bound* ip = code + start;
  ExecContext ctx(mem_);
  ctx.engine = engine;
  ctx.now_us = now_us;
  ctx.dt_us = dt_us;

  const char* const base = static_cast<const char*>(&&op_org);
#define PLC_NEXT()                                      \
  do {                                                  \
    ++ip;                                               \
    goto* static_cast<const void*>(base + ip->handler); \
  } while (0)
#define PLC_BIT(b) (*(b).bit & kBitState)
  // Contacts record their device's value, outputs the rung result they receive.
#define PLC_SEEN(v)                                                          \
  do {                                                                       \
    if constexpr (kRecord) seen[ip - code] |= static_cast<uint8_t>(1u << (v)); \
  } while (0)
#define PLC_SEEN_BIT() PLC_SEEN(PLC_BIT(*ip))

  auto coil = [](uint8_t& c, bool v) {
    if (!(c & kBitDisabled)) c = v ? kBitState : 0;
  };
  auto edge_up = [&](uint32_t slot, unsigned v) -> unsigned {
    uint8_t& e = edges[slot];
    const unsigned r = v & ~e & 1u;
    e = static_cast<uint8_t>(v);
    return r;
  };
  auto edge_down = [&](uint32_t slot, unsigned v) -> unsigned {
    uint8_t& e = edges[slot];
    const unsigned r = ~v & e & 1u;
    e = static_cast<uint8_t>(v);
    return r;
  };
  auto fault_at = [&](const Bound* b, const std::string& why) {
    set_fault(static_cast<size_t>(b - code), why);
    return false;
  };

  goto* static_cast<const void*>(base + ip->handler);

op_org: PLC_SEEN_BIT(); sp = 0; acc = PLC_BIT(*ip); PLC_NEXT();
op_org_not: PLC_SEEN_BIT(); sp = 0; acc = PLC_BIT(*ip) ^ 1u; PLC_NEXT();
op_ld: PLC_SEEN_BIT(); stack[sp++] = static_cast<uint8_t>(acc); acc = PLC_BIT(*ip); PLC_NEXT();
op_ld_not: PLC_SEEN_BIT(); stack[sp++] = static_cast<uint8_t>(acc); acc = PLC_BIT(*ip) ^ 1u; PLC_NEXT();
op_and: PLC_SEEN_BIT(); acc &= PLC_BIT(*ip); PLC_NEXT();
op_and_not: PLC_SEEN_BIT(); acc &= PLC_BIT(*ip) ^ 1u; PLC_NEXT();
op_or: PLC_SEEN_BIT(); acc |= PLC_BIT(*ip); PLC_NEXT();
op_or_not: PLC_SEEN_BIT(); acc |= PLC_BIT(*ip) ^ 1u; PLC_NEXT();
op_org_up: PLC_SEEN_BIT(); sp = 0; acc = edge_up(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_org_down: PLC_SEEN_BIT(); sp = 0; acc = edge_down(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_ld_up: PLC_SEEN_BIT(); stack[sp++] = static_cast<uint8_t>(acc); acc = edge_up(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_ld_down: PLC_SEEN_BIT(); stack[sp++] = static_cast<uint8_t>(acc); acc = edge_down(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_and_up: PLC_SEEN_BIT(); acc &= edge_up(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_and_down: PLC_SEEN_BIT(); acc &= edge_down(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_or_up: PLC_SEEN_BIT(); acc |= edge_up(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_or_down: PLC_SEEN_BIT(); acc |= edge_down(ip->arg, PLC_BIT(*ip)); PLC_NEXT();
op_and_ld: acc &= stack[--sp]; PLC_NEXT();
op_or_ld: acc |= stack[--sp]; PLC_NEXT();
op_out: PLC_SEEN(acc); coil(*ip->bit, acc); PLC_NEXT();
op_out_not: PLC_SEEN(acc); coil(*ip->bit, !acc); PLC_NEXT();
op_set: PLC_SEEN(acc); if (acc) coil(*ip->bit, true); PLC_NEXT();
op_rst: PLC_SEEN(acc); if (acc) coil(*ip->bit, false); PLC_NEXT();
op_rst_reg: {
  PLC_SEEN(acc);
  const Extra& x = *ip->extra;
  if (acc) {
    const BoundOperand& o = ops_[x.first_op];
    if (x.clears == 1) {
      coil(*o.b, false);
      rt[x.number] = 0;
      timer_rem_us_[x.number] = 0;
    } else if (x.clears == 2) {
      coil(*o.b, false);
      uint16_t* w = rc + rc_word_index(x.number);
      w[0] = 0;
      if (x.number >= kFirst32BitCounter) w[1] = 0;
    } else {
      ctx.is32 = x.is32;
      ctx.put(o, 0);
    }
  }
  PLC_NEXT();
}
op_tmr: {
  PLC_SEEN(acc);
  const Extra& x = *ip->extra;
  const uint32_t n = x.number;
  ctx.is32 = false;
  const int64_t preset = ctx.get(ops_[x.first_op]);
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
  PLC_NEXT();
}
op_ctr: {
  PLC_SEEN(acc);
  const Extra& x = *ip->extra;
  const uint32_t n = x.number;
  const bool wide = n >= kFirst32BitCounter;
  ctx.is32 = wide;
  const int64_t preset = ctx.get(ops_[x.first_op]);
  uint16_t* w = rc + rc_word_index(n);
  int64_t v = wide ? int64_t(int32_t(uint32_t(w[0]) | (uint32_t(w[1]) << 16))) : int64_t(w[0]);
  if (edge_up(x.edge, acc) && v < preset) {
    ++v;
    w[0] = static_cast<uint16_t>(v);
    if (wide) w[1] = static_cast<uint16_t>(uint64_t(v) >> 16);
  }
  coil(c_bits[n], v >= preset);
  PLC_NEXT();
}
op_fun: {
  const Extra& x = *ip->extra;
  const int n = x.n_inputs;
  ctx.inputs[n - 1] = acc;
  for (int k = n - 2; k >= 0; --k) ctx.inputs[k] = stack[--sp];
  bool en = ctx.inputs[0];
  PLC_SEEN(en);
  acc = en;
  if (x.pulse) en = edge_up(x.edge, en);
  if (en || x.fn->always_runs) {
    ctx.en = en;
    ctx.is32 = x.is32;
    ctx.instance = static_cast<uint32_t>(ip - code);
    x.fn->handler(ctx, ops_.data() + x.first_op);
  }
  PLC_NEXT();
}
op_lbl: PLC_NEXT();
op_jmp:
  PLC_SEEN(acc);
  if (acc) {
    const Bound* target = code + ip->arg;
    if (target <= ip && ++loops > loop_budget_)
      return fault_at(ip, "watchdog: more than " + std::to_string(loop_budget_) + " backward jumps in one scan");
    ip = target;
  }
  PLC_NEXT();
op_call:
  PLC_SEEN(acc);
  if (acc) {
    if (csp == kMaxCallDepth) return fault_at(ip, "CALL nested deeper than " + std::to_string(kMaxCallDepth));
    calls[csp++] = ip;
    ip = code + ip->arg;  // the LBL; PLC_NEXT steps past it
  }
  PLC_NEXT();
op_rts:
  if (csp == 0) return routine ? true : fault_at(ip, "RTS without CALL");
  ip = calls[--csp];
  PLC_NEXT();
op_rti:
  if (csp == 0) return routine ? true : fault_at(ip, "RTI outside an interrupt");
  ip = calls[--csp];
  PLC_NEXT();
op_for: {
  const Extra& x = *ip->extra;
  if (fsp == static_cast<int>(sizeof fors / sizeof fors[0])) return fault_at(ip, "FOR nested too deeply");
  ctx.is32 = false;
  const int64_t count = ctx.get(ops_[x.first_op]);
  if (count <= 0) {
    ip = code + x.number;  // the matching NEXT; PLC_NEXT steps past it
  } else {
    fors[fsp++] = {ip, count};
  }
  PLC_NEXT();
}
op_next:
  if (fsp > 0 && --fors[fsp - 1].remaining > 0) {
    if (++loops > loop_budget_)
      return fault_at(ip, "watchdog: more than " + std::to_string(loop_budget_) + " loop iterations in one scan");
    ip = fors[fsp - 1].body;
  } else if (fsp > 0) {
    --fsp;
  }
  PLC_NEXT();
op_end:
  if (!routine) return true;
  return fault_at(ip, "routine reached END without RTS/RTI");
#undef PLC_NEXT
#undef PLC_BIT
#undef PLC_SEEN
#undef PLC_SEEN_BIT
}

}  // namespace plc_cell
