#include "plc_cell/core/native/native_code.h"

#include <sys/mman.h>

#include <asmjit/x86.h>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"

namespace plc_cell::native {

namespace {

constexpr int kUnknown = -1;

bool is_template(Op op, int depth, const Step& s) {
  switch (op) {
    case Op::Org: case Op::OrgNot: case Op::And: case Op::AndNot: case Op::Or: case Op::OrNot:
      return s.bit != nullptr;
    case Op::Ld: case Op::LdNot:
      return s.bit != nullptr && depth != kUnknown && depth + 1 < Interpreter::kMaxStack;
    case Op::AndLd: case Op::OrLd:
      return depth != kUnknown && depth >= 1;
    case Op::Out: case Op::OutNot: case Op::Set: case Op::Rst:
      return s.bit != nullptr;
    default:
      return false;
  }
}

// Block stack depth after op, as the parser guarantees it inside a network. Flow
// instructions make it unknown: the instruction after a LBL, a CALL or a FOR can be reached
// from elsewhere, with whatever depth the other path left.
int depth_after(Op op, int d, const Step& s) {
  switch (op) {
    case Op::Org: case Op::OrgNot: case Op::OrgUp: case Op::OrgDown: return 0;
    case Op::Ld: case Op::LdNot: case Op::LdUp: case Op::LdDown: return d == kUnknown ? d : d + 1;
    case Op::AndLd: case Op::OrLd: return d == kUnknown || d < 1 ? kUnknown : d - 1;
    case Op::Fun: return d == kUnknown || d < s.fun_inputs - 1 ? kUnknown : d - (s.fun_inputs - 1);
    case Op::Lbl: case Op::Call: case Op::Rts: case Op::Rti: case Op::For: case Op::Next: case Op::End:
      return kUnknown;
    default: return d;  // contacts, coils, TMR, CTR, register RST, JMP not taken
  }
}

using namespace asmjit;

// The first levels of the block stack, in caller-saved registers (no spills around calls:
// a run calls nothing). edi carries acc in and is free once acc is in eax.
constexpr int kRegLevels = 6;
const x86::Gp kLevel32[kRegLevels] = {x86::r8d, x86::r9d, x86::r10d, x86::r11d, x86::ecx, x86::edi};
const x86::Gp kLevel8[kRegLevels] = {x86::r8b, x86::r9b, x86::r10b, x86::r11b, x86::cl, x86::dil};

class RunEmitter {
 public:
  explicit RunEmitter(x86::Assembler& a) : a_(a) {}

  void emit(const std::vector<Step>& steps, const std::vector<int>& depth, uint32_t first, uint32_t end) {
    base_ = nullptr;
    for (uint32_t i = first; i < end && !base_; ++i) base_ = steps[i].bit;
    a_.push(x86::rbx);
    a_.push(x86::r12);
    a_.mov(x86::eax, x86::edi);
    a_.mov(x86::rbx, reinterpret_cast<uint64_t>(base_));
    const int d0 = depth[first];
    for (int k = 0; k < std::min(d0, kRegLevels); ++k) a_.movzx(kLevel32[k], x86::byte_ptr(x86::rsi, k));
    int d = d0;
    for (uint32_t i = first; i < end; ++i) {
      one(steps[i], d);
      d = depth_after(steps[i].op, d, steps[i]);
    }
    for (int k = 0; k < std::min(d, kRegLevels); ++k) a_.mov(x86::byte_ptr(x86::rsi, k), kLevel8[k]);
    a_.pop(x86::r12);
    a_.pop(x86::rbx);
    a_.ret();
  }

 private:
  x86::Mem device(uint8_t* p) {
    const int64_t off = p - base_;
    if (off >= INT32_MIN && off <= INT32_MAX) return x86::byte_ptr(x86::rbx, static_cast<int32_t>(off));
    a_.mov(x86::r12, reinterpret_cast<uint64_t>(p));
    return x86::byte_ptr(x86::r12);
  }

  void push(int d) {
    if (d < kRegLevels) a_.mov(kLevel32[d], x86::eax);
    else a_.mov(x86::byte_ptr(x86::rsi, d), x86::al);
  }
  void combine_level(int d, bool is_or) {  // acc op= level d
    if (d < kRegLevels) {
      if (is_or) a_.or_(x86::eax, kLevel32[d]);
      else a_.and_(x86::eax, kLevel32[d]);
    } else {
      if (is_or) a_.or_(x86::al, x86::byte_ptr(x86::rsi, d));
      else a_.and_(x86::al, x86::byte_ptr(x86::rsi, d));
    }
  }
  void load(const x86::Mem& m, bool negate) {
    a_.movzx(x86::eax, m);
    if (negate) a_.not_(x86::eax);
    a_.and_(x86::eax, kBitState);
  }
  void coil_if_enabled(const x86::Mem& m, const x86::Gp& v8) {
    Label skip = a_.newLabel();
    a_.test(m, kBitDisabled);
    a_.jnz(skip);
    a_.mov(m, v8);
    a_.bind(skip);
  }

  void one(const Step& s, int d) {
    switch (s.op) {
      case Op::Org: load(device(s.bit), false); break;
      case Op::OrgNot: load(device(s.bit), true); break;
      case Op::Ld: push(d); load(device(s.bit), false); break;
      case Op::LdNot: push(d); load(device(s.bit), true); break;
      case Op::And: a_.and_(x86::al, device(s.bit)); break;  // acc is 0 or 1
      case Op::AndNot:
        a_.movzx(x86::edx, device(s.bit));
        a_.not_(x86::edx);
        a_.and_(x86::eax, x86::edx);
        break;
      case Op::Or:
      case Op::OrNot:
        a_.movzx(x86::edx, device(s.bit));
        if (s.op == Op::OrNot) a_.not_(x86::edx);
        a_.and_(x86::edx, kBitState);
        a_.or_(x86::eax, x86::edx);
        break;
      case Op::AndLd: combine_level(d - 1, false); break;
      case Op::OrLd: combine_level(d - 1, true); break;
      case Op::Out: coil_if_enabled(device(s.bit), x86::al); break;
      case Op::OutNot:
        a_.mov(x86::edx, x86::eax);
        a_.xor_(x86::edx, 1);
        coil_if_enabled(device(s.bit), x86::dl);
        break;
      case Op::Set:
      case Op::Rst: {
        Label skip = a_.newLabel();
        const x86::Mem m = device(s.bit);
        a_.test(x86::eax, x86::eax);
        a_.jz(skip);
        a_.test(m, kBitDisabled);
        a_.jnz(skip);
        a_.mov(m, s.op == Op::Set ? kBitState : 0);
        a_.bind(skip);
        break;
      }
      default: break;  // is_template() admits nothing else
    }
  }

  x86::Assembler& a_;
  uint8_t* base_ = nullptr;
};

}  // namespace

NativeCode::NativeCode() = default;
NativeCode::~NativeCode() { release(); }

void NativeCode::release() {
  if (pages_) munmap(pages_, size_);
  pages_ = nullptr;
  size_ = 0;
  runs_.clear();
  native_instructions_ = 0;
}

bool NativeCode::host_supported(std::string* why) {
  if (Environment::host().arch() == Arch::kX64) return true;
  *why = "the native engine generates x86-64 code only; this CPU is not x86-64";
  return false;
}

bool NativeCode::compile(const std::vector<Step>& steps, std::string* why) {
  release();
  if (!host_supported(why)) return false;

  std::vector<int> depth(steps.size() + 1, kUnknown);
  std::vector<Run> runs;
  for (uint32_t i = 0; i < steps.size();) {
    const int d = depth[i];
    if (!is_template(steps[i].op, d, steps[i])) {
      depth[i + 1] = depth_after(steps[i].op, d, steps[i]);
      ++i;
      continue;
    }
    uint32_t j = i;
    while (j < steps.size() && is_template(steps[j].op, depth[j], steps[j])) {
      depth[j + 1] = depth_after(steps[j].op, depth[j], steps[j]);
      ++j;
    }
    if (j - i >= kMinRun) runs.push_back(Run{i, j - i, depth[j], nullptr});
    i = j;
  }

  CodeHolder code;
  code.init(Environment::host());
  x86::Assembler a(&code);
  RunEmitter emitter(a);
  std::vector<Label> labels;
  labels.reserve(runs.size());
  for (const Run& r : runs) {
    labels.push_back(a.newLabel());
    a.align(AlignMode::kCode, 16);
    a.bind(labels.back());
    emitter.emit(steps, depth, r.first, r.first + r.length);
  }
  asmjit::Error err = code.flatten();
  if (!err) err = code.resolveUnresolvedLinks();
  if (err) {
    *why = std::string("code generation failed: ") + "asmjit error " + std::to_string(err);
    return false;
  }
  const size_t size = std::max<size_t>(code.codeSize(), 1);
  // Written while read+write, then read+execute: the pages are never both at once.
  void* pages = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (pages == MAP_FAILED) {
    *why = "no memory for the native code";
    return false;
  }
  err = code.relocateToBase(reinterpret_cast<uint64_t>(pages));
  if (!err) err = code.copyFlattenedData(pages, size, CopySectionFlags::kPadSectionBuffer);
  if (err || mprotect(pages, size, PROT_READ | PROT_EXEC) != 0) {
    munmap(pages, size);
    *why = err ? std::string("code relocation failed: ") + "asmjit error " + std::to_string(err)
               : std::string("the native code could not be made executable");
    return false;
  }
  pages_ = pages;
  size_ = size;
  for (size_t k = 0; k < runs.size(); ++k) {
    runs[k].fn = reinterpret_cast<RunFn>(static_cast<char*>(pages) + code.labelOffsetFromBase(labels[k]));
    native_instructions_ += runs[k].length;
  }
  runs_ = std::move(runs);
  return true;
}

}  // namespace plc_cell::native
