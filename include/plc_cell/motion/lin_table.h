#pragma once
// A FUN147 MHSP0 linear-interpolation program: its steps, the text form
// (SPD / LIN|LINE / [WAIT|EXT] / GOTO ... MEND) and the register form
// (15 registers per step + 2, docs/motion.md "FUN147 register layout").
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

constexpr int kLinStepWords = 15;
constexpr uint16_t kLinTableMagic = 0x147A;  // SR+1: marks a FUN147 table in this layout
constexpr int kIllegalLin = 60;              // "Illegal linear interpolation command"

struct LinStep {
  Step flow;          // speed (vector), transfer (WAIT Time/contact, EXT), GOTO; motion fields unused
  bool line = false;  // LINE: ends at its vector speed, the next step continues from it (no stop)
  bool abs = false;
  bool ut = false;
  uint8_t axes = 0;   // bit n: Ps n is named (a blank, or an ADR constant 0, is inactive)
  std::array<Operand, 4> stroke{};  // per axis Ps0-Ps3: constant or Rn/Dn (32-bit pair)
  bool operator==(const LinStep& o) const;
};

struct LinTable {
  std::vector<LinStep> steps;
  uint8_t axes() const;  // every axis any step names: the axes a run holds
};

// Parses the text form; false with the code and line of the first error.
bool parse_lin_table(const std::string& text, LinTable* out, TableError* err);
std::string format_lin_table(const LinTable& t);
// Register form: N * 15 + 2 words.
std::vector<uint16_t> encode_lin_table(const LinTable& t);
bool decode_lin_table(const uint16_t* regs, size_t n, LinTable* out, TableError* err);
// LINE chain rules (no transfer, GOTO NEXT, not the last step).
bool check_lin_table(const LinTable& t, TableError* err, const std::vector<int>& lines = {});

}  // namespace motion
}  // namespace plc_cell
