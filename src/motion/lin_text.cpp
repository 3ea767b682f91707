// The text form of a FUN147 linear-interpolation program: the FUN140 step skeleton
// (program_text.h) with LIN / LINE as the motion line.
#include <cstdio>
#include <sstream>

#include "plc_cell/motion/lin_table.h"
#include "program_text.h"

namespace plc_cell {
namespace motion {

bool LinStep::operator==(const LinStep& o) const {
  return flow == o.flow && line == o.line && abs == o.abs && ut == o.ut && axes == o.axes && stroke == o.stroke;
}

uint8_t LinTable::axes() const {
  uint8_t m = 0;
  for (const auto& s : steps) m |= s.axes;
  return m;
}

namespace {

using text::Fail;

// LIN ADR|ABS, s0, s1, s2, s3 [, Ut|Ps]: one stroke (or target) per axis Ps0-Ps3.
void lin_operands(const std::string& rest, LinStep* st) {
  std::vector<std::string> t = text::split_commas(rest);
  if (t.size() == 5) t.push_back("PS");  // default resolution: Ps (as FUN140)
  if (t.size() != 6) throw Fail{kIllegalLin, "expected ADR|ABS,s0,s1,s2,s3,Ut|Ps (blank = axis not used)"};
  if (t[0] == "ADR") st->abs = false;
  else if (t[0] == "ABS") st->abs = true;
  else throw Fail{kIllegalLin, "coordinate must be ADR or ABS, not '" + t[0] + "'"};
  for (int n = 0; n < 4; ++n) {
    const std::string& s = t[1 + n];
    if (s.empty()) continue;  // blank: inactive
    const Operand op = text::value_operand(s, 2, -99999999, 99999999, 32, 33, "stroke");
    if (op.kind == Operand::Const && op.value == 0 && !st->abs) continue;  // ADR 0: inactive
    st->stroke[n] = op;
    st->axes |= uint8_t(1u << n);
  }
  if (t[5] == "UT") st->ut = true;
  else if (t[5] == "PS") st->ut = false;
  else throw Fail{kIllegalLin, "resolution must be Ut or Ps, not '" + t[5] + "'"};
  if (st->axes == 0) throw Fail{kIllegalLin, "no axis moves (every stroke blank or 0)"};
}

}  // namespace

bool parse_lin_table(const std::string& src, LinTable* out, TableError* err) {
  LinTable t;
  std::vector<Step> flow;
  std::vector<int> lines;
  text::Syntax syn;
  syn.motion_names = "LIN/LINE";
  syn.motion = [&](const std::string& kw, const std::string& rest, size_t i) {
    if (kw != "LIN" && kw != "LINE") return false;
    if (i == SIZE_MAX) return true;
    t.steps.resize(i + 1);
    t.steps[i].line = kw == "LINE";
    lin_operands(rest, &t.steps[i]);
    return true;
  };
  // FUN140's motion commands and ACT are not FUN147 commands (manual: SPD, LIN,
  // LINE, WAIT, EXT, GOTO, MEND).
  syn.reject = [](const std::string& kw) {
    return kw == "DRV" || kw == "DRVC" || kw == "DRVZ" || kw == "ACT" ? kIllegalLin : 0;
  };
  if (!text::parse_program(src, syn, &flow, &lines, err)) return false;
  t.steps.resize(flow.size());
  for (size_t i = 0; i < flow.size(); ++i) t.steps[i].flow = flow[i];
  if (!check_lin_table(t, err, lines)) return false;
  *out = std::move(t);
  return true;
}

bool check_lin_table(const LinTable& t, TableError* err, const std::vector<int>& lines) {
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const LinStep& s = t.steps[i];
    const auto fail = [&](const std::string& m) {
      *err = {34, i < lines.size() ? lines[i] : 0, "step " + std::to_string(i + 1) + ": " + m};
      return false;
    };
    if (s.axes == 0 || (s.axes >> 4) != 0) {
      *err = {kIllegalLin, i < lines.size() ? lines[i] : 0, "step " + std::to_string(i + 1) + ": no axis moves"};
      return false;
    }
    if (!s.line) continue;
    if (s.flow.transfer != Transfer::None || s.flow.goto_kind != Step::Next)
      return fail("LINE continues with the next step: only GOTO NEXT");
    if (i + 1 == t.steps.size()) return fail("a LINE chain must end with LIN");
  }
  return true;
}

std::string format_lin_table(const LinTable& t) {
  std::ostringstream o;
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const LinStep& s = t.steps[i];
    o << text::format_head(i, s.flow) << "    " << (s.line ? "LINE " : "LIN ")
      << (s.abs ? "ABS" : "ADR");
    for (int n = 0; n < 4; ++n) o << "," << ((s.axes >> n) & 1 ? text::op_text(s.stroke[n]) : " ");
    o << "," << (s.ut ? "Ut" : "Ps") << "\n" << text::format_flow(s.flow);
  }
  o << "MEND\n";
  return o.str();
}

}  // namespace motion
}  // namespace plc_cell
