#pragma once
// Rung coverage of one IL program, summed over every Plc that ran it: a scenario-test run
// gives each case a fresh cell, and the totals say what all the cases together exercised.
// This is the one header a test runner includes; the report and its outputs come with it.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/program.h"
#include "plc_cell/coverage/mcdc.h"
#include "plc_cell/coverage/outputs.h"
#include "plc_cell/coverage/report.h"

namespace plc_cell {
namespace coverage {

class Recorder {
 public:
  Recorder() = default;
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;
  Recorder(Recorder&&) = default;
  Recorder& operator=(Recorder&&) = default;

  // Starts recording plc's loaded program (takes plc.locked internally). Throws
  // plc_cell::Error if plc has no program, is already recorded (by this recorder or
  // another), or its program differs from the one this recorder holds (file or
  // instructions). Loading another program into plc ends the recording (what was
  // recorded until then still counts at detach).
  // names: the cell's signals, which the reports show beside the addresses (the first
  // attach that gives any is kept: the cells of one program normally name it alike).
  void attach(Plc& plc, const SignalNames& names = {});
  // Stops recording and adds what was recorded to the totals. Safe to call twice, and for
  // a Plc that was never attached. Call it before plc is destroyed.
  void detach(Plc& plc);
  // True until a Plc has been attached: the recorder holds no program yet.
  bool empty() const { return !program_; }
  const std::string& program_file() const;

  // What report() reads: the program and, per instruction, the values it saw
  // (Interpreter::kSeenOff | kSeenOn), ORed over every detached recording.
  const Program& program() const;
  const std::vector<uint8_t>& seen() const { return seen_; }
  // Per instruction, the FUN's mnemonic (empty for other instructions), taken from the
  // first attached Plc's instruction set.
  const std::vector<std::string>& fun_names() const { return fun_names_; }
  const SignalNames& signal_names() const { return names_; }
  // Recordings detached so far (each Plc's run counts once).
  uint32_t runs() const { return runs_; }
  // Contact k (in the order of its network's contacts) of network n was shown to decide
  // it alone (MC/DC, mcdc.h), in some detached recording.
  bool independent(size_t n, size_t k) const { return vectors_.independent(n, k); }

 private:
  struct Attachment {
    Plc* plc;
    std::unique_ptr<uint8_t[]> seen;  // the interpreter writes here while the Plc scans
    std::unique_ptr<McdcSampler> sampler;  // hooked on the Plc's engine: reads and clears seen
  };
  std::unique_ptr<Program> program_;
  std::vector<std::string> fun_names_;
  SignalNames names_;
  std::vector<uint8_t> seen_;
  std::vector<Attachment> attached_;
  uint32_t runs_ = 0;
  McdcVectors vectors_;
};

}  // namespace coverage
}  // namespace plc_cell
