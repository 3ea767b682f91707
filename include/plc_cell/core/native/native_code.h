#pragma once
// Machine code for the networks of an IL program (docs/native-engine.md).
//
// A run is a sequence of instructions that have a machine-code template: every contact
// (edge contacts with their edge memories too), ANDLD/ORLD, the bit coils OUT, OUT NOT,
// SET, RST, and TMR, CTR, register RST and FUN as calls to the interpreter's own bodies of
// them (Step::call), or of a FUN's word form (Step::words), so the two engines share those
// semantics by construction. The flow
// instructions (LBL, JMP, CALL, RTS, RTI, FOR, NEXT, END) end a run and stay on the
// interpreter's dispatch loop. Inside a run the accumulator and the block stack live in
// registers (the first four levels; deeper levels in the interpreter's stack array), and
// every device is an absolute address bound at load time.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"

namespace plc_cell::native {

// What a run passes to the calls it makes, and where it finds the block stack.
struct Frame {
  void* self;      // the interpreter
  void* ctx;       // its ExecContext for this run of the program
  uint8_t* stack;  // its block stack: levels below a run's entry depth are read from here,
                   // and levels below its exit depth left here, as the interpreter would
  uint32_t dt_us;  // time since the previous scan (TMR)
};

// Set in what a call or a run returns when a FUN handler threw: the interpreter's fault is
// set, and the run stops there, as the interpreter's loop does.
constexpr unsigned kFault = 0x80000000u;

// An instruction executed by a call: arg and imm are its own data, acc the rung result
// (a FUN: its inputs, bit k input k). Returns the rung result after it, or kFault.
using CallFn = unsigned (*)(Frame* frame, const void* arg, unsigned acc, uint32_t imm);

// One bound instruction as the generator sees it.
struct Step {
  Op op = Op::Lbl;
  uint8_t* bit = nullptr;   // the device of a contact or coil
  uint8_t* edge = nullptr;  // the edge memory of TU/TD contact
  CallFn call = nullptr;    // TMR, CTR, register RST, FUN
  const void* arg = nullptr;
  uint32_t imm = 0;
  bool may_fault = false;   // the call runs a FUN handler, which may throw
  uint8_t fun_inputs = 1;   // a FUN's number of inputs (it pops all but one block)
  // A one-input FUN without .P that has a word form for its operands: called directly while
  // its EN is on, with its operand pointers in the argument registers (instead of call).
  WordHandler words = nullptr;
  void* const* word_ops = nullptr;
  uint8_t word_count = 0;   // operand pointers it passes
};

// acc is the rung result on entry (0/1). Returns the rung result, or kFault.
using RunFn = unsigned (*)(unsigned acc, Frame* frame);

struct Run {
  uint32_t first = 0;   // index of its first instruction
  uint32_t length = 0;  // instructions it covers
  int32_t depth_after = 0;  // block stack depth when it returns
  RunFn fn = nullptr;
};

class NativeCode {
 public:
  // Shorter runs stay on the interpreter: entering a run costs about one dispatch.
  static constexpr uint32_t kMinRun = 3;

  NativeCode();
  ~NativeCode();
  NativeCode(const NativeCode&) = delete;
  NativeCode& operator=(const NativeCode&) = delete;

  // False, with the reason, where this CPU has no code generator.
  static bool host_supported(std::string* why);

  // Generates the runs of steps. False, with the reason, if the generator failed; then
  // runs() is empty.
  bool compile(const std::vector<Step>& steps, std::string* why);
  const std::vector<Run>& runs() const { return runs_; }
  uint32_t native_instructions() const { return native_instructions_; }
  size_t code_bytes() const { return size_; }

 private:
  void release();

  std::vector<Run> runs_;
  uint32_t native_instructions_ = 0;
  void* pages_ = nullptr;  // read+execute once written, never both writable and executable
  size_t size_ = 0;
};

}  // namespace plc_cell::native
