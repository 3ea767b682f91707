#pragma once
// A FUN140 positioning program ("motion table"): its steps, the manual's text form
// and the register form (9 registers per step + 2, docs/motion.md "Register layout").
#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell {
namespace motion {

constexpr int kMaxSteps = 250;
constexpr int kStepWords = 9;
constexpr int kHeaderWords = 2;
constexpr uint16_t kTableMagic = 0x140A;  // SR+1: marks a table written in this layout

// A constant, or a register read when the step starts: R/D index (32-bit pair for
// speed and stroke, one word for times and GOTO).
struct Operand {
  enum Kind : uint8_t { Const = 0, R = 1, D = 2 } kind = Const;
  int32_t value = 0;  // the constant, or the register number
  bool operator==(const Operand& o) const { return kind == o.kind && value == o.value; }
};

enum class Motion : uint8_t { Drv = 0, Drvc = 1, Drvz = 2 };
enum class Transfer : uint8_t { None = 0, WaitTime = 1, WaitContact = 2, Act = 3, Ext = 4 };
enum class ContactArea : uint8_t { X = 0, Y = 1, M = 2, S = 3 };

struct Step {
  Operand speed;
  Motion motion = Motion::Drv;
  bool abs = false;
  int dir = 0;       // +1 '+', -1 '-', 0 blank (sign of the stroke)
  Operand stroke;
  bool ut = false;   // resolution Ut (else Ps)
  int zero_mode = 0; // DRVZ MD0-MD2
  Transfer transfer = Transfer::None;
  Operand time;      // WAIT Time / ACT, in 0.01 s
  ContactArea contact_area = ContactArea::X;
  int contact = 0;   // WAIT/EXT contact number
  enum GotoKind : uint8_t { Next = 0, Number = 1, R = 2, D = 3 } goto_kind = Next;
  int goto_value = 0;
  bool operator==(const Step& o) const;
};

struct Table {
  std::vector<Step> steps;
};

// A parse or decode failure: the manual's error code (30-53) and, for text, the line.
struct TableError {
  int code = 0;  // 0 = none
  int line = 0;  // 1-based text line (0: whole program / register form)
  std::string message;
};

// Parses the manual's text form (docs/motion.md "Text form"). Returns false and fills
// *err (code and line) on the first error.
bool parse_table(const std::string& text, Table* out, TableError* err);
// A zero return (DRVZ MDmode at speed pps, docs/motion.md "Homing") as a one-step table,
// for a unit-run homing (the ROS command): speed and mode are checked as in any table.
bool homing_table(uint32_t speed, int mode, Table* out, TableError* err);
std::string format_table(const Table& t);

// Register form: N * 9 + 2 words.
std::vector<uint16_t> encode_table(const Table& t);
// Reads from regs (available words: n); false with code 34/35/36 on a bad image.
bool decode_table(const uint16_t* regs, size_t n, Table* out, TableError* err);

// Chain rules checked after parsing or decoding (DRVC chains, DRVZ after DRVC).
bool check_table(const Table& t, TableError* err, const std::vector<int>& lines = {});

}  // namespace motion
}  // namespace plc_cell
