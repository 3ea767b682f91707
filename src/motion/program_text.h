#pragma once
// Internal: the pieces of the manual's positioning-program text form shared by the
// FUN140 parser (table_text.cpp) and the FUN147 parser (lin_text.cpp): operands,
// the step skeleton SPD / motion / [transfer] / GOTO ... MEND, and the register
// encoding of a step's flow part (speed, transfer, GOTO). Not installed.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {
namespace text {

// A parse failure inside a line: the manual's code and a message.
struct Fail {
  int code;
  std::string msg;
};

std::string upper(std::string s);
std::string trim(const std::string& s);
bool parse_int(const std::string& s, int64_t* v);
std::vector<std::string> split_commas(const std::string& s);
// Rn / Dn (words = 2: the 32-bit pair must fit). False if s is not a register at all;
// true with op->value = -1 and *why set if it is one but out of range.
bool reg_operand(const std::string& s, int words, Operand* op, std::string* why);
// Constant or Rn/Dn; throws Fail{reg_code} for a bad register, Fail{val_code} for a
// constant outside lo..hi.
Operand value_operand(const std::string& s, int words, int64_t lo, int64_t hi, int reg_code, int val_code,
                      const char* what);
std::string op_text(const Operand& o);

// The program skeleton. `motion` parses the motion line of the step being built
// (throws Fail) and returns false if kw is not one of its commands; `reject`
// returns a code (non-zero) for a known keyword this instruction does not accept.
struct Syntax {
  std::function<bool(const std::string& kw, const std::string& rest, size_t step)> motion;
  std::function<int(const std::string& kw)> reject;
  const char* motion_names;  // for messages: "DRV/DRVC/DRVZ"
};
// Fills steps (flow part: speed, transfer, GOTO) and the line of each SPD.
bool parse_program(const std::string& text, const Syntax& syn, std::vector<Step>* steps,
                   std::vector<int>* step_lines, TableError* err);
// "003 SPD 5000" (the step's first line) and its WAIT/EXT/GOTO lines, as the manual writes them.
std::string format_head(size_t index, const Step& s);
std::string format_flow(const Step& s);

// The 2-word header of a register image: SR+0 = N (1-250), SR+1 = magic; N steps of
// step_words must fit in n. False with code 34/35/36.
bool decode_header(const uint16_t* r, size_t n, uint16_t magic, int step_words, int* steps, TableError* err);

// Register form of the flow part: bits 8-14 of the command word (transfer, GOTO
// kind, contact area), the time/contact word and the GOTO word.
uint16_t flow_bits(const Step& s);
uint16_t flow_time_word(const Step& s);
// Decodes them into s (time kind from tk); false with *why on a bad field.
bool decode_flow(uint16_t cmd, uint16_t time_word, uint16_t goto_word, uint32_t tk, int steps, Step* s,
                 std::string* why);

}  // namespace text
}  // namespace motion
}  // namespace plc_cell
