#pragma once
// Internal: what one instruction looks like on the ladder (its element, without position).
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace ladder {

// The cell's name of an address: the first signal naming it, in file order.
class Names {
 public:
  explicit Names(const Signals& signals);
  std::string of(const Address& a) const;

 private:
  std::map<uint64_t, std::string> names_;
};

uint64_t address_key(const Address& a);

class Drawer {
 public:
  Drawer(const Program& p, const Names& names, const FunctionTable* functions,
         const std::vector<std::string>& line_comments)
      : p_(p), names_(names), functions_(functions), line_comments_(line_comments) {}

  // The element of instruction i (a contact, an output or a flow instruction).
  Element element(uint32_t i) const;
  // The input names of the FUN at instruction i, `count` of them.
  std::vector<std::string> fun_inputs(uint32_t i, size_t count) const;

 private:
  void contact(const Instruction& in, Element* e) const;
  void coil(const Instruction& in, Element* e) const;
  void timer_counter(const Instruction& in, Element* e) const;
  void fun(const Instruction& in, Element* e) const;
  void flow(const Instruction& in, Element* e) const;
  FunOperand operand(const Operand& o) const;

  const Program& p_;
  const Names& names_;
  const FunctionTable* functions_;
  const std::vector<std::string>& line_comments_;  // by source line
};

}  // namespace ladder
}  // namespace plc_cell
