#pragma once
// A parsed IL program drawn as ladder networks: each network (ORG up to the next ORG or
// flow instruction) as a grid of elements and wires, the shape the monitor's page draws
// (docs/ladder.md). The layout also holds what power flow needs (flow.h): which power
// node feeds each element and each wire.
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"

namespace plc_cell {
namespace ladder {

using Signals = std::vector<std::pair<std::string, Address>>;  // name, address; file order

struct FunOperand {
  std::string name;     // the operand's name in the FUN's table (S, D, Sa, EQ, ...)
  std::string text;     // as shown: an address, K<n> for a constant, or a label
  std::string address;  // what to read for its live value; empty for a constant
  std::string signal;   // the cell's name for the address, if it has one
};

struct FunInput {  // one input of a FUN box (EN first; more come from LD blocks)
  std::string name;
  int row = 0;
};

struct Element {
  int id = 0;
  int row = 0;
  int col = 0;
  // contact, coil, timer, counter, fun, jump, call, label, flow
  std::string type;
  // contact: no|nc|up|down; coil: out|out_not|set|rst; flow: RTS|RTI|FOR|NEXT|END
  std::string form;
  std::string address;  // contact, coil, timer, counter
  std::string name;     // the cell's signal name of the address ("" if none)
  int line = 0;
  int instruction = -1;  // index in Program::code
  std::string comment;   // the comment at the end of its IL line
  // timer, counter
  std::string preset;
  std::string preset_address;       // when the preset is a register
  std::vector<std::string> values;  // T5, RT5 / C0, RC0
  // fun
  int fun = -1;
  std::string mnemonic;
  bool pulse = false;
  bool d32 = false;
  std::vector<FunOperand> operands;  // fun; FOR's count
  std::vector<FunInput> inputs;      // fun
  std::string label;                 // jump, call, label
  // Power (not drawn): the node that feeds it and, for a contact, the node it drives and
  // the bit it reads.
  int in = -1;
  int out = -1;
  Address bit{};
};

// Horizontal: on row `row` from boundary `from` to boundary `to` (columns).
// Vertical: at boundary `col` from row `from` to row `to`.
struct Wire {
  int id = 0;
  bool vertical = false;
  int row = 0;
  int col = 0;
  int from = 0;
  int to = 0;
  int node = -1;  // the power node it carries
};

// One electrical node of a rung. No inputs: the left rail (always powered). A contact:
// powered when its input node is and the contact is closed. Otherwise: powered when
// any of its inputs is (the right side of a parallel block).
struct PowerNode {
  int contact = -1;  // element id
  std::vector<int> from;
};

struct IlLine {
  int line = 0;
  std::string text;
};

struct Network {
  int index = 0;
  int line = 0;          // of its first instruction
  std::string comment;   // the comment lines right above it, markers stripped
  bool drawable = true;
  std::string reason;    // why it is not drawable
  std::vector<IlLine> il;
  int rows = 0;
  int cols = 0;  // outputs sit at col == cols
  std::vector<Element> elements;
  std::vector<Wire> wires;
  std::vector<PowerNode> nodes;  // in evaluation order
  uint32_t first = 0;  // instructions [first, end) of Program::code
  uint32_t end = 0;
};

struct Layout {
  std::string file;
  uint64_t version = 0;
  std::vector<Network> networks;
  Signals signals;
};

// Lays out every network of the program. `text` is the IL source the program was parsed
// from (for comments and IL lines); `functions` gives FUN mnemonics and input names (without
// it a FUN shows as "FUN n"). Never throws for a program the parser accepted: what cannot be
// drawn is a network with drawable == false and its reason.
Layout layout(const Program& program, std::string_view text, const Signals& signals = {},
              const FunctionTable* functions = nullptr);

// Every address to read to draw the network live: contacts, coils, timer and counter
// values, presets in registers, FUN operands. Each once, in drawing order.
std::vector<Address> addresses(const Network& network);

}  // namespace ladder
}  // namespace plc_cell
