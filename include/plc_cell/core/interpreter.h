#pragma once
// Executes a Program against a Memory. Single-threaded; the scan engine owns it.
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/core/native/native_code.h"
#include "plc_cell/core/program.h"

namespace plc_cell {

class ScanEngine;

// What a FUN handler sees of the instruction being executed.
class ExecContext {
 public:
  Memory& mem;
  ScanEngine* engine = nullptr;  // null when the interpreter runs on its own (tests)
  bool en = false;               // the first input
  std::array<bool, 4> inputs{};  // every input, in the spec's order
  bool is32 = false;
  uint64_t now_us = 0;           // virtual time at the start of this scan
  uint32_t dt_us = 0;            // time since the previous scan
  uint32_t instance = 0;         // index of this instruction: a key for per-instruction state

  explicit ExecContext(Memory& m) : mem(m) {}

  // Values are signed as on the FBs: 16-bit operands read as int16, 32-bit as int32.
  int64_t get(const BoundOperand& o) const;
  uint32_t get_raw(const BoundOperand& o) const;  // unsigned bit pattern
  void put(const BoundOperand& o, int64_t v) const;  // truncates to the operand width
  void flag(const BoundOperand& o, bool v) const;    // no-op if the optional operand is absent
};

class Interpreter {
 public:
  static constexpr int kMaxCallDepth = 16;
  static constexpr int kMaxForDepth = 5;
  static constexpr int kMaxStack = 32;

  Interpreter(Memory& mem, const FunctionTable& functions);

  // Binds the program to memory. Edge memories and timer remainders start fresh.
  void load(const Program& program);
  // Binds as load() does, keeping what a change in RUN keeps (docs/online-change.md): every
  // timer's running state and remainder, and the edge memory of each edge instruction the
  // new program still has (online_change.h, carried_edges).
  void load_keeping_state(const Program& program);
  bool loaded() const { return !code_.empty(); }
  // A TMR whose rung was on at its last run: the timer is timing (or up and held).
  bool timer_running(uint32_t timer) const { return timer_running_[timer] != 0; }
  const Program& program() const { return program_; }

  // Time base of each timer in microseconds (FBs default: T0-49 10 ms, T50-199 100 ms, T200-255 1 s).
  void set_timer_base(uint32_t timer, uint32_t base_us) { timer_base_us_[timer] = base_us; }
  uint32_t timer_base(uint32_t timer) const { return timer_base_us_[timer]; }
  // Backward jumps and loops allowed per scan before the watchdog trips.
  void set_loop_budget(uint64_t n) { loop_budget_ = n; }

  // Runs the main program once. Returns false on a runtime fault (see fault()).
  bool run_main(uint64_t now_us, uint32_t dt_us, ScanEngine* engine);
  // Runs the routine that starts at label (an interrupt service routine ends with RTI).
  bool run_routine(const std::string& label, uint64_t now_us, ScanEngine* engine);
  const std::string& fault() const { return fault_; }

  // Forget edge memories and timer remainders (on STOP -> RUN).
  void reset_state();

  // Coverage (docs/coverage.md). While seen is set (one byte per instruction of the loaded
  // program), each contact ORs into its byte the value of the device it reads, and each
  // coil, TMR, CTR, JMP and CALL the rung result it receives, and each FUN its EN:
  // kSeenOff for 0, kSeenOn for 1. nullptr stops recording, and so does load(). Recording
  // runs its own instantiation of the run loop: the loop without it is unchanged.
  static constexpr uint8_t kSeenOff = 1;
  static constexpr uint8_t kSeenOn = 2;
  void record_into(uint8_t* seen);
  uint8_t* recording() const { return seen_; }

  // The native engine (docs/native-engine.md): the networks compiled to machine code by
  // load() (TMR, CTR, register RST and FUN as calls to this class's own bodies of them);
  // the flow instructions keep their handlers here. Takes effect
  // at the next load(). Where the code cannot be generated the interpreter runs the whole
  // program and engine_status() says why. Coverage recording always runs the interpreter.
  void use_native(bool on);
  bool native_requested() const { return want_native_; }
  bool native_active() const { return native_ != nullptr; }
  const native::NativeCode* native_code() const { return native_.get(); }
  // One line for logs and diagnostics: which engine runs the loaded program, and why.
  const std::string& engine_status() const { return engine_status_; }

 private:
  // One bound instruction in 16 bytes, so a large ladder stays cache-friendly:
  // contacts and coils carry their bit pointer; the rest point to an Extra.
  struct Extra {
    uint32_t edge;    // edge memory (CTR, pulse FUN)
    uint32_t number;  // timer/counter number; FOR: matching NEXT
    uint32_t first_op;
    uint16_t n_ops;
    uint8_t n_inputs;
    bool is32;
    bool pulse;
    uint8_t clears;   // RST of a timer (1) or counter (2) also clears its value
    uint32_t index;   // the instruction's own index (a FUN's ExecContext::instance)
    const FunctionSpec* fn;
    WordHandler words;         // FUN: its word form for these operands, or null (fn->handler)
    void* const* word_ops;     // its six operand pointers (function_table.h, WordHandler)
    const uint16_t* preset;    // TMR, 16-bit CTR: the preset's word (a register or a constant), or null
  };
  struct Bound {
    int32_t handler;  // offset of this opcode's handler from the first one (direct threading)
    uint32_t arg;     // edge memory of a TU/TD contact, or the target of JMP/CALL
    union {
      uint8_t* bit;
      Extra* extra;
      const native::Run* run;  // the entry of a native run (native_code_ only)
    };
  };
  static_assert(sizeof(Bound) == 16, "keep a bound instruction at 16 bytes");

  static constexpr uint32_t kInitDispatch = ~0u;
  bool execute(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine);
  bool run_plain(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine);
  bool run_recording(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine);
  bool run_native(uint32_t pc, uint64_t now_us, uint32_t dt_us, ScanEngine* engine, bool routine);
  // The main program when one machine-code run covers it up to its END (whole_main_).
  bool run_whole_main(uint64_t now_us, uint32_t dt_us, ScanEngine* engine);
  void bind_native();
  void native_step(size_t i, native::Step* s);
  // The bodies of register RST, TMR, CTR and FUN (interpreter_steps.inc): the run loops and
  // the native engine's machine code (through the native_* calls) execute these same
  // functions, so the two engines share their semantics by construction.
  unsigned edge_up(uint32_t slot, unsigned v);
  void reset_step(const Extra& x, unsigned acc, ExecContext& ctx);
  int64_t timer_preset(const Extra& x, ExecContext& ctx) const;
  void timer_step(uint32_t n, int64_t preset, unsigned acc, uint32_t dt_us);
  void counter_step(const Extra& x, unsigned acc, ExecContext& ctx);
  // ctx.inputs set; returns the rung result, with native::kFault if the handler threw.
  unsigned fun_step(const Extra& x, ExecContext& ctx);
  bool call_handler(const Extra& x, ExecContext& ctx);  // false: it threw, and the fault is set
  static unsigned native_reset(native::Frame* f, const void* x, unsigned acc, uint32_t);
  static unsigned native_timer(native::Frame* f, const void* preset, unsigned acc, uint32_t timer);
  static unsigned native_timer_bound(native::Frame* f, const void* x, unsigned acc, uint32_t);
  static unsigned native_counter(native::Frame* f, const void* x, unsigned acc, uint32_t);
  static unsigned native_fun(native::Frame* f, const void* x, unsigned inputs, uint32_t);
  // load(): binds instruction in (its edge slot `edge`) into b and x, its operands onto
  // ops; op becomes the opcode it runs as. False: it needs no Extra.
  bool bind(const Program& program, const Instruction& in, uint32_t edge, Bound* b, Extra* x, Op* op,
            std::vector<BoundOperand>* ops) const;
  // After bind(): a FUN's word form and its operand pointers, a TMR's preset word, where the
  // operands allow them (interpreter_words.cpp). Constants get slots in constants_.
  void bind_words(const Instruction& in, Extra* x);
  void* word_pointer(const BoundOperand& o, OperandRole role, bool is32);
  void set_fault(size_t pc, const std::string& why);

  Memory& mem_;
  const FunctionTable& functions_;
  Program program_;
  // One handler per opcode, then the native-run entry.
  static constexpr size_t kNativeEntry = static_cast<size_t>(Op::End) + 1;
  using HandlerOffsets = std::array<int32_t, kNativeEntry + 1>;
  HandlerOffsets handler_of_{};
  HandlerOffsets recording_handler_of_{};
  HandlerOffsets native_handler_of_{};
  std::vector<Bound> code_;
  std::vector<Op> bound_op_;          // the handler each instruction runs, for recorded_code_
  std::vector<Bound> recorded_code_;  // code_ bound to the recording run loop's handlers
  uint8_t* seen_ = nullptr;
  bool want_native_ = false;
  std::unique_ptr<native::NativeCode> native_;
  std::vector<Bound> native_code_;  // code_ bound to run_native, native runs at their first instruction
  // The run from the first instruction when the main program's END comes right after it:
  // the scan enters it with no dispatch loop around it (most programs of straight rungs).
  const native::Run* whole_main_ = nullptr;
  std::string engine_status_ = "interpreter";
  std::vector<Extra> extras_;
  std::vector<BoundOperand> ops_;
  std::deque<std::array<void*, 6>> word_ops_;  // deques: what they hold never moves
  std::deque<std::array<uint16_t, 2>> constants_;  // constant operands as words (low word first)
  std::vector<uint8_t> edges_;
  std::array<uint32_t, 256> timer_base_us_{};
  std::array<uint64_t, 256> timer_rem_us_{};
  std::array<uint8_t, 256> timer_running_{};
  uint64_t loop_budget_ = 1000000;
  std::string fault_;
};

}  // namespace plc_cell
