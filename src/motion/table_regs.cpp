// Register form of a FUN140 program (AMBIG-15: the manual's figure is lost; this
// layout is plc_cell's, documented in docs/motion.md so an MMI can edit it).
#include "plc_cell/motion/table.h"
#include "program_text.h"

namespace plc_cell {
namespace motion {

namespace {
// Word 0 (command word) bit fields.
constexpr int kMotionShift = 0;    // 2 bits: 0 DRV, 1 DRVC, 2 DRVZ
constexpr int kAbsBit = 2;
constexpr int kDirShift = 3;       // 2 bits: 0 blank, 1 +, 2 -
constexpr int kUtBit = 5;
constexpr int kZeroShift = 6;      // 2 bits: DRVZ MD0-MD2
// Bits 8-15: transfer, GOTO kind, contact area (text::flow_bits, shared with FUN147).
// Word 1: operand kinds (2 bits each): speed, stroke, time.
uint32_t field(uint16_t w, int shift, int bits) { return (w >> shift) & ((1u << bits) - 1); }
}  // namespace

std::vector<uint16_t> encode_table(const Table& t) {
  std::vector<uint16_t> r(kHeaderWords + kStepWords * t.steps.size(), 0);
  r[0] = static_cast<uint16_t>(t.steps.size());
  r[1] = kTableMagic;
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    uint16_t* w = &r[kHeaderWords + kStepWords * i];
    const uint32_t dir = s.dir > 0 ? 1 : s.dir < 0 ? 2 : 0;
    w[0] = static_cast<uint16_t>((uint32_t(s.motion) << kMotionShift) | (uint32_t(s.abs) << kAbsBit) |
                                 (dir << kDirShift) | (uint32_t(s.ut) << kUtBit) |
                                 (uint32_t(s.zero_mode) << kZeroShift) | text::flow_bits(s));
    w[1] = static_cast<uint16_t>(uint32_t(s.speed.kind) | (uint32_t(s.stroke.kind) << 2) | (uint32_t(s.time.kind) << 4));
    w[2] = static_cast<uint16_t>(uint32_t(s.speed.value) & 0xFFFF);
    w[3] = static_cast<uint16_t>(uint32_t(s.speed.value) >> 16);
    w[4] = static_cast<uint16_t>(uint32_t(s.stroke.value) & 0xFFFF);
    w[5] = static_cast<uint16_t>(uint32_t(s.stroke.value) >> 16);
    w[6] = text::flow_time_word(s);
    w[7] = static_cast<uint16_t>(s.goto_value);
    w[8] = static_cast<uint16_t>(i + 1);  // step number: a check an MMI edit keeps
  }
  return r;
}

bool decode_table(const uint16_t* r, size_t n, Table* out, TableError* err) {
  int steps = 0;
  if (!text::decode_header(r, n, kTableMagic, kStepWords, &steps, err)) return false;
  Table t;
  for (int i = 0; i < steps; ++i) {
    const uint16_t* w = &r[kHeaderWords + kStepWords * i];
    const auto bad = [&](const std::string& m) {
      *err = {34, 0, "step " + std::to_string(i + 1) + ": " + m};
      return false;
    };
    if (w[8] != i + 1) return bad("check word SR+" + std::to_string(kHeaderWords + kStepWords * i + 8) + " must be the step number");
    Step s;
    const uint32_t m = field(w[0], kMotionShift, 2), d = field(w[0], kDirShift, 2), z = field(w[0], kZeroShift, 2);
    if (m > 2) return bad("bad command");
    if (d > 2) return bad("bad direction");
    s.motion = static_cast<Motion>(m);
    s.abs = field(w[0], kAbsBit, 1);
    s.dir = d == 1 ? 1 : d == 2 ? -1 : 0;
    s.ut = field(w[0], kUtBit, 1);
    s.zero_mode = static_cast<int>(z);
    if (s.motion == Motion::Drvz && z > 2) {
      *err = {50, 0, "step " + std::to_string(i + 1) + ": illegal DRVZ mode"};
      return false;
    }
    const uint32_t sk = field(w[1], 0, 2), pk = field(w[1], 2, 2), tk = field(w[1], 4, 2);
    if (sk > 2 || pk > 2 || tk > 2 || (w[1] >> 6) != 0) return bad("bad operand kinds word");
    s.speed = {static_cast<Operand::Kind>(sk), static_cast<int32_t>(uint32_t(w[2]) | (uint32_t(w[3]) << 16))};
    s.stroke = {static_cast<Operand::Kind>(pk), static_cast<int32_t>(uint32_t(w[4]) | (uint32_t(w[5]) << 16))};
    if (s.speed.kind == Operand::Const && (s.speed.value < 1 || s.speed.value > 921600)) {
      *err = {31, 0, "step " + std::to_string(i + 1) + ": speed out of range 1~921600"};
      return false;
    }
    if (s.stroke.kind == Operand::Const && (s.stroke.value < -99999999 || s.stroke.value > 99999999)) {
      *err = {33, 0, "step " + std::to_string(i + 1) + ": stroke out of range"};
      return false;
    }
    std::string why;
    if (!text::decode_flow(w[0], w[6], w[7], tk, steps, &s, &why)) return bad(why);
    t.steps.push_back(s);
  }
  if (!check_table(t, err)) return false;
  *out = std::move(t);
  return true;
}

}  // namespace motion
}  // namespace plc_cell
