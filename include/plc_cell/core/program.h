#pragma once
// A parsed IL program: a flat instruction list with addresses still symbolic.
// The Interpreter binds it to one Memory (pointers) when it is loaded.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"

namespace plc_cell {

enum class Op : uint8_t {
  // Contacts. Org starts a network, Ld opens a block for AndLd/OrLd.
  Org, OrgNot, Ld, LdNot, And, AndNot, Or, OrNot,
  OrgUp, OrgDown, LdUp, LdDown, AndUp, AndDown, OrUp, OrDown,
  AndLd, OrLd,
  // Coils.
  Out, OutNot, Set, Rst, RstReg,
  Tmr, Ctr, Fun,
  // Flow.
  Lbl, Jmp, Call, Rts, Rti, For, Next, End,
};

struct Operand {
  enum class Kind : uint8_t { Const, Reg16, Reg32, Bits16, Bits32, Bit };
  Kind kind = Kind::Const;
  int64_t k = 0;   // Const
  Address addr{};  // for the others
  std::string name;  // the operand name it was given for (S, D, EQ, ...)
  bool present = true;  // optional operands may be absent
  std::string text;     // a Label operand's name (upper case)
  int column = 0;       // where its value starts on its line (1-based): tools that rewrite it
};

struct Instruction {
  Op op = Op::End;
  bool is32 = false;   // .D modifier
  bool pulse = false;  // .P modifier: execute on the rising edge of EN only
  uint16_t fun = 0;    // function number for Op::Fun
  Address addr{};      // contact/coil/timer/counter target
  uint32_t target = 0; // resolved jump/call target (instruction index)
  std::string label;   // Lbl/Jmp/Call label text
  std::vector<Operand> operands;  // Tmr/Ctr preset, Fun operands in spec order
  int line = 0;
  int column = 0;
};

struct Program {
  std::string file;
  std::vector<Instruction> code;
  uint32_t main_end = 0;                    // index of the END that closes the main program
  std::map<std::string, uint32_t> labels;   // label -> instruction index of its Lbl
  uint32_t edge_slots = 0;                  // number of edge memories the program needs
  std::vector<uint32_t> edge_slot_of;       // per instruction, its edge memory (or ~0u)
};

}  // namespace plc_cell
