#pragma once
// Internal: a network's instructions evaluated symbolically, as the interpreter evaluates
// them with values: contacts combine into series/parallel expressions (LD pushes, ANDLD and
// ORLD pop), and each output takes the expression it was given. Outputs that share one
// expression form a group; a later group must extend the one before in series (a branch
// off the rung), anything else is not a planar ladder and gets a reason.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/program.h"

namespace plc_cell {
namespace ladder {

struct Expr;
using ExprP = std::shared_ptr<const Expr>;

struct Expr {
  enum class Kind { Contact, Series, Parallel };
  Kind kind = Kind::Contact;
  uint32_t instruction = 0;  // Contact
  std::vector<ExprP> parts;  // Series, Parallel (never nested in their own kind)
};

ExprP contact_expr(uint32_t instruction);
ExprP series(const ExprP& a, const ExprP& b);
ExprP parallel(const ExprP& a, const ExprP& b);

struct Group {
  std::vector<ExprP> extension;   // series parts added after the previous group's exit
  std::vector<uint32_t> outputs;  // instructions, top to bottom
};

struct Rung {
  std::string reason;  // empty: drawable
  std::vector<Group> groups;  // the first one's extension is the whole trunk
  // A FUN with several inputs: each input's expression (EN first); then it is the only
  // output of the network.
  std::vector<ExprP> fun_inputs;
  uint32_t fun = 0;
};

// Instructions [first, end) of one network (starting with an ORG form). A FUN takes as
// many inputs as blocks are open before it (the parser checked them against its table).
Rung build_rung(const Program& p, uint32_t first, uint32_t end);

bool is_contact(Op op);
bool is_output(Op op);
bool is_flow(Op op);  // LBL, RTS, RTI, FOR, NEXT, END: a network of its own

}  // namespace ladder
}  // namespace plc_cell
