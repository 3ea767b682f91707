#include "plc_cell/core/interpreter.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>

#include "plc_cell/core/error.h"
#include "plc_cell/core/online_change.h"

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
  run_plain(kInitDispatch, 0, 0, nullptr, false);
  run_recording(kInitDispatch, 0, 0, nullptr, false);
  run_native(kInitDispatch, 0, 0, nullptr, false);
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
    x.index = static_cast<uint32_t>(i);
    x.first_op = static_cast<uint32_t>(ops.size());
    if (bind(program, in, edge, &b, &x, &op, &ops)) {
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
  word_ops_.clear();
  constants_.clear();
  for (size_t i = 0; i < extra_of.size(); ++i)
    if (extra_of[i] >= 0) bind_words(program_.code[i], &extras_[static_cast<size_t>(extra_of[i])]);
  record_into(nullptr);  // a recording belongs to the program it was started on
  edges_.assign(program_.edge_slots, 0);  // sized before the machine code binds its addresses
  bind_native();
  reset_state();
}

void Interpreter::load_keeping_state(const Program& program) {
  const Program old = program_;
  const std::vector<uint8_t> old_edges = edges_;
  const auto rem = timer_rem_us_;
  const auto running = timer_running_;
  load(program);
  timer_rem_us_ = rem;
  timer_running_ = running;
  const std::vector<uint32_t> from = carried_edges(old, program_);
  for (size_t slot = 0; slot < from.size() && slot < edges_.size(); ++slot)
    if (from[slot] < old_edges.size()) edges_[slot] = old_edges[from[slot]];
}

bool Interpreter::bind(const Program& program, const Instruction& in, uint32_t edge, Bound* b, Extra* x, Op* op,
                       std::vector<BoundOperand>* ops) const {
  switch (in.op) {
    case Op::Jmp:
    case Op::Call:
      b->arg = program.labels.at(in.label);
      return false;
    case Op::RstReg:
    case Op::For:
      x->number = in.target;
      ops->push_back(bind_operand(mem_, in.operands.at(0)));
      return true;
    case Op::Tmr:
    case Op::Ctr:
      x->number = in.addr.index;
      ops->push_back(bind_operand(mem_, in.operands.at(0)));
      return true;
    case Op::Fun:
      x->fn = functions_.find(in.fun);
      if (!x->fn) throw Error("FUN " + std::to_string(in.fun) + " is not available");
      x->n_inputs = static_cast<uint8_t>(x->fn->inputs.size());
      x->n_ops = static_cast<uint16_t>(in.operands.size());
      for (const auto& o : in.operands) ops->push_back(bind_operand(mem_, o));
      return true;
    case Op::Rst:
      if (in.addr.area == Area::T || in.addr.area == Area::C) {
        x->clears = in.addr.area == Area::T ? 1 : 2;
        x->number = in.addr.index;
        *op = Op::RstReg;  // a timer/counter reset runs the register path
        ops->push_back(BoundOperand{});
        ops->back().b = mem_.bits(in.addr.area) + in.addr.index;
        return true;
      }
      [[fallthrough]];
    default:
      b->arg = edge;
      if (in.op <= Op::Rst && in.op != Op::AndLd && in.op != Op::OrLd)
        b->bit = mem_.bits(in.addr.area) + in.addr.index;
      return false;
  }
}

void Interpreter::use_native(bool on) {
  want_native_ = on;
  if (loaded()) bind_native();
}

void Interpreter::bind_native() {
  whole_main_ = nullptr;
  native_.reset();
  native_code_.clear();
  if (!want_native_) {
    engine_status_ = "interpreter";
    return;
  }
  std::vector<native::Step> steps(program_.code.size());
  for (size_t i = 0; i < steps.size(); ++i) native_step(i, &steps[i]);
  const auto t0 = std::chrono::steady_clock::now();
  auto nc = std::make_unique<native::NativeCode>();
  std::string why;
  if (!nc->compile(steps, &why)) {
    engine_status_ = "native engine unavailable (" + why + "): the program runs on the interpreter";
    return;
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  native_code_ = code_;
  for (size_t i = 0; i < native_code_.size(); ++i)
    native_code_[i].handler = native_handler_of_[static_cast<size_t>(bound_op_[i])];
  for (const native::Run& r : nc->runs()) {
    native_code_[r.first].handler = native_handler_of_[kNativeEntry];
    native_code_[r.first].run = &r;
    if (r.first == 0 && bound_op_[r.length] == Op::End) whole_main_ = &r;
  }
  char line[200];
  std::snprintf(line, sizeof line, "native: %u of %zu instructions in %zu machine-code runs (%zu bytes, %.2f ms)",
                nc->native_instructions(), program_.code.size(), nc->runs().size(), nc->code_bytes(), ms);
  engine_status_ = line;
  native_ = std::move(nc);
}

// What the generator needs of instruction i: its device and edge memory, or the call that
// executes it (interpreter_steps.inc) with its Extra, or a FUN's word form.
void Interpreter::native_step(size_t i, native::Step* s) {
  const Op op = bound_op_[i];
  s->op = op;
  if (op <= Op::Rst && op != Op::AndLd && op != Op::OrLd) s->bit = code_[i].bit;
  if (op >= Op::OrgUp && op <= Op::OrDown) s->edge = edges_.data() + code_[i].arg;
  if (op != Op::RstReg && op != Op::Tmr && op != Op::Ctr && op != Op::Fun) return;
  const Extra& x = *code_[i].extra;
  s->arg = &x;
  s->fun_inputs = x.n_inputs;
  switch (op) {
    case Op::RstReg: s->call = &Interpreter::native_reset; break;
    case Op::Ctr: s->call = &Interpreter::native_counter; break;
    case Op::Tmr:
      s->call = x.preset ? &Interpreter::native_timer : &Interpreter::native_timer_bound;
      if (x.preset) s->arg = x.preset;
      s->imm = x.number;
      break;
    default:  // FUN
      if (x.words && !x.pulse) {
        s->words = x.words;
        s->word_ops = x.word_ops;
        s->word_count = static_cast<uint8_t>(x.n_ops);
        break;
      }
      s->call = &Interpreter::native_fun;
      s->may_fault = !x.words;
      break;
  }
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
  std::fill(edges_.begin(), edges_.end(), 0);  // in place: the machine code holds their addresses
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
  if (whole_main_ && native_ && !seen_) return run_whole_main(now_us, dt_us, engine);
  return execute(0, now_us, dt_us, engine, false);
}

// What run_native does for such a program, without its loop's frame: the run from the
// first instruction (block stack empty, rung result 0), then END.
bool Interpreter::run_whole_main(uint64_t now_us, uint32_t dt_us, ScanEngine* engine) {
  uint8_t stack[kMaxStack];
  ExecContext ctx(mem_);
  ctx.engine = engine;
  ctx.now_us = now_us;
  ctx.dt_us = dt_us;
  native::Frame frame{this, &ctx, stack, dt_us};
  return !(whole_main_->fn(0, &frame) & native::kFault);  // a FUN handler threw: the fault is set
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

#include "interpreter_steps.inc"

bool Interpreter::execute(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine) {
  if (seen_) return run_recording(pc, now_us, dt_us, engine, routine);
  return native_ ? run_native(pc, now_us, dt_us, engine, routine) : run_plain(pc, now_us, dt_us, engine, routine);
}

// The plain loop and the recording loop are two ordinary functions from one source. As a
// template instantiation (a COMDAT function, which GCC neither splits into hot and cold
// parts nor places among the others) the plain loop measured slower than before coverage
// existed; as an ordinary function it is level (docs/performance.md, "Coverage recording").
#define PLC_RUN run_plain
#define PLC_RECORD 0
#define PLC_NATIVE 0
#include "interpreter_run.inc"
#undef PLC_RUN
#undef PLC_RECORD
#undef PLC_NATIVE
#define PLC_RUN run_recording
#define PLC_RECORD 1
#define PLC_NATIVE 0
#include "interpreter_run.inc"
#undef PLC_RUN
#undef PLC_RECORD
#undef PLC_NATIVE
// The native engine's driver: the same handlers, plus the entry into a machine-code run.
#define PLC_RUN run_native
#define PLC_RECORD 0
#define PLC_NATIVE 1
#include "interpreter_run.inc"
#undef PLC_RUN
#undef PLC_RECORD
#undef PLC_NATIVE

}  // namespace plc_cell
