#include "run_emitter.h"

#include <algorithm>
#include <climits>
#include <cstddef>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell::native {

bool is_template(const Step& s, int depth) {
  const bool pushes_into_range = depth != kUnknownDepth && depth + 1 < Interpreter::kMaxStack;
  switch (s.op) {
    case Op::Org: case Op::OrgNot: case Op::And: case Op::AndNot: case Op::Or: case Op::OrNot:
    case Op::Out: case Op::OutNot: case Op::Set: case Op::Rst:
      return s.bit != nullptr;
    case Op::OrgUp: case Op::OrgDown: case Op::AndUp: case Op::AndDown: case Op::OrUp: case Op::OrDown:
      return s.bit != nullptr && s.edge != nullptr;
    case Op::Ld: case Op::LdNot:
      return s.bit != nullptr && pushes_into_range;
    case Op::LdUp: case Op::LdDown:
      return s.bit != nullptr && s.edge != nullptr && pushes_into_range;
    case Op::AndLd: case Op::OrLd:
      return depth != kUnknownDepth && depth >= 1;
    case Op::RstReg: case Op::Tmr: case Op::Ctr:
      return s.call != nullptr;
    case Op::Fun:  // its inputs beyond EN come off the block stack
      if (s.words) return s.word_count <= 6;
      return s.call != nullptr && (s.fun_inputs == 1 || (depth != kUnknownDepth && depth >= s.fun_inputs - 1));
    default:
      return false;
  }
}

int depth_after(const Step& s, int d) {
  switch (s.op) {
    case Op::Org: case Op::OrgNot: case Op::OrgUp: case Op::OrgDown: return 0;
    case Op::Ld: case Op::LdNot: case Op::LdUp: case Op::LdDown: return d == kUnknownDepth ? d : d + 1;
    case Op::AndLd: case Op::OrLd: return d == kUnknownDepth || d < 1 ? kUnknownDepth : d - 1;
    case Op::Fun:
      return d == kUnknownDepth || d < s.fun_inputs - 1 ? kUnknownDepth : d - (s.fun_inputs - 1);
    case Op::Lbl: case Op::Call: case Op::Rts: case Op::Rti: case Op::For: case Op::Next: case Op::End:
      return kUnknownDepth;
    default: return d;  // contacts, coils, TMR, CTR, register RST, JMP not taken
  }
}

namespace {

using namespace asmjit;

// Registers: eax the rung result; rbp the Frame; rbx the base that devices are addressed
// from; r12-r15 the first block stack levels. All but eax are callee-saved, so they live
// through the calls of TMR, CTR, RST and FUN. r10 and r11 are scratch for addresses.
//
// Only bit 0 of the rung result and of the register levels is the value: a contact combines
// the device's whole byte (its disable flag too) and the other bits are cleared only where a
// whole value leaves the register (a coil's store, a call's argument, the stack array).
constexpr int kRegLevels = 4;
const x86::Gp kLevel32[kRegLevels] = {x86::r12d, x86::r13d, x86::r14d, x86::r15d};
const x86::Gp kLevel8[kRegLevels] = {x86::r12b, x86::r13b, x86::r14b, x86::r15b};
const x86::Gp kSaved[] = {x86::rbp, x86::rbx, x86::r12, x86::r13, x86::r14, x86::r15};
const x86::Gp kArgs[6] = {x86::rdi, x86::rsi, x86::rdx, x86::rcx, x86::r8, x86::r9};

class Emitter {
 public:
  Emitter(x86::Assembler& a, uint8_t* base) : a_(a), base_(base), fault_(a.newLabel()) {
    andn_ = CpuInfo::host().hasFeature(CpuFeatures::X86::kBMI);
  }

  void prologue(int d0) {
    for (const x86::Gp& r : kSaved) a_.push(r);
    a_.sub(x86::rsp, 8);  // six pushes and the return address: realign to 16 for the calls
    a_.mov(x86::rbp, x86::rsi);
    a_.mov(x86::eax, x86::edi);
    clean_ = true;  // the interpreter's rung result is 0 or 1
    a_.mov(x86::rbx, reinterpret_cast<uint64_t>(base_));
    if (d0 > 0) load_stack_pointer();
    for (int k = 0; k < std::min(d0, kRegLevels); ++k) a_.movzx(kLevel32[k], x86::byte_ptr(x86::r10, k));
  }

  // The levels below depth d go back to the stack array, cleared to their value bit.
  void epilogue(int d) {
    clean();
    if (d > 0) load_stack_pointer();
    for (int k = 0; k < std::min(d, kRegLevels); ++k) {
      a_.and_(kLevel32[k], 1);
      a_.mov(x86::byte_ptr(x86::r10, k), kLevel8[k]);
    }
    leave();
    if (!faults_) return;
    a_.bind(fault_);  // eax holds kFault: the run stops where the handler threw
    leave();
  }

  void step(const Step& s, int d) {
    if (s.words) word_call(s);
    else if (s.call) call(s, d);
    else if (is_edge(s.op)) edge(s, d);
    else if (s.op >= Op::Out) coil(s);
    else contact(s, d);
  }

 private:
  void leave() {
    a_.add(x86::rsp, 8);
    for (int k = static_cast<int>(std::size(kSaved)) - 1; k >= 0; --k) a_.pop(kSaved[k]);
    a_.ret();
  }
  void clean() {  // the rung result becomes exactly 0 or 1
    if (!clean_) a_.and_(x86::eax, 1);
    clean_ = true;
  }
  void load_stack_pointer() { a_.mov(x86::r10, x86::qword_ptr(x86::rbp, offsetof(Frame, stack))); }

  x86::Mem device(uint8_t* p) {
    const int64_t off = p - base_;
    if (off >= INT32_MIN && off <= INT32_MAX) return x86::byte_ptr(x86::rbx, static_cast<int32_t>(off));
    a_.mov(x86::r11, reinterpret_cast<uint64_t>(p));
    return x86::byte_ptr(x86::r11);
  }
  void pointer_into(const x86::Gp& r, const void* p) {
    const int64_t off = static_cast<const uint8_t*>(p) - base_;
    if (!p) a_.xor_(r.r32(), r.r32());
    else if (off >= INT32_MIN && off <= INT32_MAX) a_.lea(r, x86::ptr(x86::rbx, static_cast<int32_t>(off)));
    else a_.mov(r, reinterpret_cast<uint64_t>(p));
  }
  x86::Mem deep_level(int d) {  // a block stack level beyond the registers
    load_stack_pointer();
    return x86::byte_ptr(x86::r10, d);
  }

  void push(int d) {  // block stack level d takes the rung result
    if (d < kRegLevels) {
      a_.mov(kLevel32[d], x86::eax);
      return;
    }
    clean();  // the stack array holds whole values
    a_.mov(deep_level(d), x86::al);
  }
  void level_into(const x86::Gp& r32, int d) {  // whole value
    if (d < kRegLevels) {
      a_.mov(r32, kLevel32[d]);
      a_.and_(r32, 1);
    } else {
      a_.movzx(r32, deep_level(d));
    }
  }
  void combine_level(int d, bool is_or) {  // acc op= level d
    if (d < kRegLevels) {
      if (is_or) a_.or_(x86::eax, kLevel32[d]);
      else a_.and_(x86::eax, kLevel32[d]);
    } else {
      if (is_or) a_.or_(x86::al, deep_level(d));
      else a_.and_(x86::al, deep_level(d));
    }
  }
  void load(const x86::Mem& m, bool negate) {
    a_.movzx(x86::eax, m);
    if (negate) a_.not_(x86::eax);
  }

  void contact(const Step& s, int d) {
    switch (s.op) {
      case Op::Org: load(device(s.bit), false); break;
      case Op::OrgNot: load(device(s.bit), true); break;
      case Op::Ld: push(d); load(device(s.bit), false); break;
      case Op::LdNot: push(d); load(device(s.bit), true); break;
      case Op::And: a_.and_(x86::al, device(s.bit)); break;
      case Op::Or: a_.or_(x86::al, device(s.bit)); break;
      case Op::AndNot:
        a_.movzx(x86::edx, device(s.bit));
        if (andn_) {
          a_.andn(x86::eax, x86::edx, x86::eax);
        } else {
          a_.not_(x86::edx);
          a_.and_(x86::eax, x86::edx);
        }
        break;
      case Op::OrNot:
        a_.movzx(x86::edx, device(s.bit));
        a_.not_(x86::edx);
        a_.or_(x86::eax, x86::edx);
        break;
      case Op::AndLd: combine_level(d - 1, false); break;
      case Op::OrLd: combine_level(d - 1, true); break;
      default: break;  // is_template() admits no other contact
    }
    clean_ = false;
  }

  // TU/TD: the device's value v against its edge memory e, which then takes v.
  // Rising: v & ~e & 1; falling: ~v & e & 1. The result combines as a plain contact's.
  void edge(const Step& s, int d) {
    const bool falling = s.op == Op::OrgDown || s.op == Op::LdDown || s.op == Op::AndDown || s.op == Op::OrDown;
    a_.movzx(x86::ecx, device(s.bit));
    a_.and_(x86::ecx, kBitState);
    const x86::Mem e = device(s.edge);
    a_.movzx(x86::edx, e);
    a_.mov(e, x86::cl);
    if (falling) a_.not_(x86::ecx);
    else a_.not_(x86::edx);
    a_.and_(x86::edx, x86::ecx);
    a_.and_(x86::edx, 1);
    switch (s.op) {
      case Op::LdUp: case Op::LdDown: push(d); [[fallthrough]];
      case Op::OrgUp: case Op::OrgDown: a_.mov(x86::eax, x86::edx); clean_ = true; break;
      case Op::AndUp: case Op::AndDown: a_.and_(x86::eax, x86::edx); clean_ = true; break;
      default: a_.or_(x86::eax, x86::edx); break;
    }
  }

  void coil_if_enabled(const x86::Mem& m, const x86::Gp& v8) {
    Label skip = a_.newLabel();
    a_.test(m, kBitDisabled);
    a_.jnz(skip);
    a_.mov(m, v8);
    a_.bind(skip);
  }
  void coil(const Step& s) {
    const x86::Mem m = device(s.bit);
    if (s.op == Op::Out) {
      clean();
      coil_if_enabled(m, x86::al);
    } else if (s.op == Op::OutNot) {
      clean();
      a_.mov(x86::edx, x86::eax);
      a_.xor_(x86::edx, 1);
      coil_if_enabled(m, x86::dl);
    } else {  // SET, RST
      Label skip = a_.newLabel();
      a_.test(x86::al, 1);
      a_.jz(skip);
      a_.test(m, kBitDisabled);
      a_.jnz(skip);
      a_.mov(m, s.op == Op::Set ? kBitState : 0);
      a_.bind(skip);
    }
  }

  // s.call(frame, s.arg, acc, s.imm); a FUN's inputs as bits, input k from the level it pops.
  void call(const Step& s, int d) {
    const int n = s.op == Op::Fun ? s.fun_inputs : 1;
    clean();
    a_.mov(x86::edx, x86::eax);
    if (n > 1) a_.shl(x86::edx, n - 1);
    for (int k = 0; k + 1 < n; ++k) {
      level_into(x86::ecx, d - (n - 1) + k);
      if (k > 0) a_.shl(x86::ecx, k);
      a_.or_(x86::edx, x86::ecx);
    }
    a_.mov(x86::rdi, x86::rbp);
    a_.mov(x86::rsi, reinterpret_cast<uint64_t>(s.arg));
    a_.mov(x86::ecx, s.imm);
    a_.call(Imm(reinterpret_cast<uint64_t>(s.call)));
    if (s.may_fault) {
      faults_ = true;
      a_.test(x86::eax, x86::eax);
      a_.js(fault_);
    }
  }

  // A one-input FUN's word form, called while EN is on with its operand pointers as arguments;
  // the rung result after it is its EN.
  void word_call(const Step& s) {
    Label skip = a_.newLabel();
    if (clean_) a_.test(x86::eax, x86::eax);
    else a_.and_(x86::eax, 1);
    clean_ = true;
    a_.jz(skip);
    for (int k = 0; k < s.word_count; ++k) pointer_into(kArgs[k], s.word_ops[k]);
    a_.call(Imm(reinterpret_cast<uint64_t>(s.words)));
    a_.mov(x86::eax, 1);
    a_.bind(skip);
  }

  static bool is_edge(Op op) { return op >= Op::OrgUp && op <= Op::OrDown; }

  x86::Assembler& a_;
  uint8_t* const base_;
  Label fault_;          // where a run returns kFault
  bool faults_ = false;  // whether a call may return kFault
  bool clean_ = true;    // whether eax is exactly the rung result (0 or 1)
  bool andn_ = false;    // BMI1
};

}  // namespace

void emit_run(x86::Assembler& a, const std::vector<Step>& steps, const std::vector<int>& depth, uint32_t first,
              uint32_t end) {
  uint8_t* base = nullptr;
  for (uint32_t i = first; i < end && !base; ++i) base = steps[i].bit ? steps[i].bit : steps[i].edge;
  Emitter e(a, base);
  e.prologue(depth[first]);
  for (uint32_t i = first; i < end; ++i) e.step(steps[i], depth[i]);
  e.epilogue(depth[end]);
}

}  // namespace plc_cell::native
