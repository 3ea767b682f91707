#pragma once
// Mutants of an IL program: one instruction changed the way a slip of the pen would
// change it (docs/testing-your-cell.md, "Mutation testing").
#include <string>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"

namespace plc_cell {
namespace mutation {

struct Mutant {
  int line = 0;            // 1, 2, ... in the program file
  std::string op;          // the operator: "invert contact", "AND/OR", "edge", ...
  std::string before;      // the instruction as written, comment dropped: "AND X3"
  std::string after;       // "AND NOT X3"; empty: the instruction deleted
  // "AND X3 → AND NOT X3", "OUT Y0 → (deleted)"
  std::string change() const { return before + " \u2192 " + (after.empty() ? "(deleted)" : after); }
};

// Every mutant of the program, in line order and, on a line, in operator order: a contact
// inverted (NOT added or dropped); AND <-> OR; an edge contact TU <-> TD, an edge to its
// level and a level to a rising edge; ANDLD <-> ORLD; SET <-> RST of a discrete; a coil
// (OUT, SET, RST) deleted; a TMR/CTR constant preset +1, -1, x2 and /2; then, operand by
// operand, a FUN's (or FOR's) constant +1 and -1, and FUN17 CMP's result flag given to
// another relation (EQ, GT, LT). lines: the program file; program: the same text as the
// cell's parser read it, whose operands say which words are constants in every form the
// parser accepts; functions: the instruction set it was parsed with.
std::vector<Mutant> mutants(const std::vector<std::string>& lines, const Program& program,
                            const FunctionTable& functions);

// The program text with m applied.
std::string apply(const std::vector<std::string>& lines, const Mutant& m);

}  // namespace mutation
}  // namespace plc_cell
