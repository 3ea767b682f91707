#pragma once
// The machine-code templates of the native engine (docs/native-engine.md): which
// instructions have one, the block stack depth they leave, and the x86-64 code of a run.
#include <cstdint>
#include <vector>

#include <asmjit/x86.h>

#include "plc_cell/core/native/native_code.h"

namespace plc_cell::native {

constexpr int kUnknownDepth = -1;

// Whether s has a template at block stack depth `depth` (kUnknownDepth where it can be
// reached from elsewhere).
bool is_template(const Step& s, int depth);

// Block stack depth after s, as the parser guarantees it inside a network. Flow
// instructions make it unknown: the instruction after a LBL, a CALL or a FOR can be reached
// from elsewhere, with whatever depth the other path left.
int depth_after(const Step& s, int depth);

// Emits steps [first, end) as one function (RunFn); depth[i] is the depth before step i.
void emit_run(asmjit::x86::Assembler& a, const std::vector<Step>& steps, const std::vector<int>& depth,
              uint32_t first, uint32_t end);

}  // namespace plc_cell::native
