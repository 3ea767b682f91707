#pragma once
// An instruction written back as IL, for messages and for a report whose source file
// cannot be read: the same mnemonics the parser reads (docs/program-format.md).
#include <string>

#include "plc_cell/core/program.h"

namespace plc_cell {
namespace coverage {

// "AND NOT X4", "TMR T50 15", "FUN 8D S=DR0 D=DR2", "CALL ADD_TEN".
std::string instruction_text(const Instruction& in);
// The mnemonic alone, with its modifier: "AND NOT", "OUT", "TMR", "FUN 8D", "CALL".
std::string mnemonic(const Instruction& in);

}  // namespace coverage
}  // namespace plc_cell
