// Register form of a FUN147 program (AMBIG-15: the manual's figure is lost; this
// layout is plc_cell's, docs/motion.md "FUN147 register layout").
#include "plc_cell/motion/lin_table.h"
#include "program_text.h"

namespace plc_cell {
namespace motion {

namespace {
// Word 0: b0 LINE, b1 ABS, b2 Ut, b3 = 0, b4-7 axis mask, b8-14 flow (text::flow_bits), b15 = 0.
constexpr uint16_t kLineMask = 1u << 0, kAbsMask = 1u << 1, kUtMask = 1u << 2;
constexpr int kMaskShift = 4;
// Word 1: operand kinds, 2 bits each: speed, s0, s1, s2, s3, time.
int kind_shift(int operand) { return 2 * operand; }
constexpr int kStrokeWord = 4, kTimeWord = 12, kGotoWord = 13, kCheckWord = 14;

uint32_t pair(const uint16_t* w) { return uint32_t(w[0]) | (uint32_t(w[1]) << 16); }
void put_pair(uint16_t* w, int32_t v) {
  w[0] = static_cast<uint16_t>(uint32_t(v) & 0xFFFF);
  w[1] = static_cast<uint16_t>(uint32_t(v) >> 16);
}
}  // namespace

std::vector<uint16_t> encode_lin_table(const LinTable& t) {
  std::vector<uint16_t> r(kHeaderWords + kLinStepWords * t.steps.size(), 0);
  r[0] = static_cast<uint16_t>(t.steps.size());
  r[1] = kLinTableMagic;
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const LinStep& s = t.steps[i];
    uint16_t* w = &r[kHeaderWords + kLinStepWords * i];
    w[0] = static_cast<uint16_t>((s.line ? kLineMask : 0) | (s.abs ? kAbsMask : 0) | (s.ut ? kUtMask : 0) |
                                 (uint32_t(s.axes) << kMaskShift) | text::flow_bits(s.flow));
    uint32_t kinds = uint32_t(s.flow.speed.kind) | (uint32_t(s.flow.time.kind) << kind_shift(5));
    put_pair(&w[2], s.flow.speed.value);
    for (int n = 0; n < 4; ++n) {
      kinds |= uint32_t(s.stroke[n].kind) << kind_shift(1 + n);
      put_pair(&w[kStrokeWord + 2 * n], s.stroke[n].value);
    }
    w[1] = static_cast<uint16_t>(kinds);
    w[kTimeWord] = text::flow_time_word(s.flow);
    w[kGotoWord] = static_cast<uint16_t>(s.flow.goto_value);
    w[kCheckWord] = static_cast<uint16_t>(i + 1);
  }
  return r;
}

bool decode_lin_table(const uint16_t* r, size_t n, LinTable* out, TableError* err) {
  int steps = 0;
  if (!text::decode_header(r, n, kLinTableMagic, kLinStepWords, &steps, err)) return false;
  LinTable t;
  for (int i = 0; i < steps; ++i) {
    const uint16_t* w = &r[kHeaderWords + kLinStepWords * i];
    const auto bad = [&](int code, const std::string& m) {
      *err = {code, 0, "step " + std::to_string(i + 1) + ": " + m};
      return false;
    };
    if (w[kCheckWord] != i + 1) return bad(34, "check word must be the step number");
    if (w[0] & (1u << 3)) return bad(kIllegalLin, "bit 3 of the command word must be 0");
    LinStep s;
    s.line = w[0] & kLineMask;
    s.abs = w[0] & kAbsMask;
    s.ut = w[0] & kUtMask;
    s.axes = static_cast<uint8_t>((w[0] >> kMaskShift) & 0xF);
    const uint32_t kinds = w[1];
    for (int k = 0; k < 6; ++k)
      if (((kinds >> kind_shift(k)) & 3) > 2) return bad(34, "bad operand kinds word");
    if (kinds >> 12) return bad(34, "bad operand kinds word");
    s.flow.speed = {static_cast<Operand::Kind>(kinds & 3), static_cast<int32_t>(pair(&w[2]))};
    if (s.flow.speed.kind == Operand::Const && (s.flow.speed.value < 1 || s.flow.speed.value > 921600))
      return bad(31, "speed out of range 1~921600");
    for (int a = 0; a < 4; ++a) {
      if (!((s.axes >> a) & 1)) continue;  // an unused axis's words are ignored
      s.stroke[a] = {static_cast<Operand::Kind>((kinds >> kind_shift(1 + a)) & 3),
                     static_cast<int32_t>(pair(&w[kStrokeWord + 2 * a]))};
      if (s.stroke[a].kind == Operand::Const && (s.stroke[a].value < -99999999 || s.stroke[a].value > 99999999))
        return bad(33, "stroke out of range");
    }
    std::string why;
    if (!text::decode_flow(w[0], w[kTimeWord], w[kGotoWord], (kinds >> kind_shift(5)) & 3, steps, &s.flow, &why))
      return bad(34, why);
    if (s.flow.transfer == Transfer::Act) return bad(kIllegalLin, "ACT is not a FUN147 transfer condition");
    t.steps.push_back(s);
  }
  if (!check_lin_table(t, err)) return false;
  *out = std::move(t);
  return true;
}

}  // namespace motion
}  // namespace plc_cell
