// The manual's text form of a FUN140 program: parse (line-precise errors with the
// manual's codes) and format.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

#include "plc_cell/motion/params.h"
#include "plc_cell/motion/table.h"
#include "program_text.h"

namespace plc_cell {
namespace motion {

bool Step::operator==(const Step& o) const {
  return speed == o.speed && motion == o.motion && abs == o.abs && dir == o.dir && stroke == o.stroke &&
         ut == o.ut && zero_mode == o.zero_mode && transfer == o.transfer && time == o.time &&
         contact_area == o.contact_area && contact == o.contact && goto_kind == o.goto_kind &&
         goto_value == o.goto_value;
}

namespace {

using text::Fail;
using text::split_commas;
using text::value_operand;

void drive_operands(const std::string& rest, Step* st) {
  std::vector<std::string> t = split_commas(rest);
  // The manual's examples also write ADR+,D100,Ut (no comma after ADR).
  if (!t.empty() && (t[0] == "ADR+" || t[0] == "ADR-")) {
    const std::string d(1, t[0][3]);
    t[0] = "ADR";
    t.insert(t.begin() + 1, d);
  }
  if (t.size() == 3) t.push_back("PS");  // default resolution: Ps
  if (t.size() != 4) throw Fail{34, "expected coord,dir,stroke,res (e.g. ADR,+,10000,Ps)"};
  if (t[0] == "ADR") st->abs = false;
  else if (t[0] == "ABS") st->abs = true;
  else throw Fail{34, "coordinate must be ADR or ABS, not '" + t[0] + "'"};
  if (t[1] == "+") st->dir = 1;
  else if (t[1] == "-") st->dir = -1;
  else if (t[1].empty()) st->dir = 0;
  else throw Fail{34, "direction must be +, - or blank, not '" + t[1] + "'"};
  if (st->abs && st->dir != 0) throw Fail{34, "ABS takes no direction (write ABS, ,value,res)"};
  st->stroke = value_operand(t[2], 2, -99999999, 99999999, 32, 33, "stroke");
  if (st->dir != 0 && st->stroke.kind == Operand::Const && st->stroke.value < 0)
    throw Fail{33, "a negative stroke needs a blank direction"};
  if (t[3] == "UT") st->ut = true;
  else if (t[3] == "PS") st->ut = false;
  else throw Fail{34, "resolution must be Ut or Ps, not '" + t[3] + "'"};
}

}  // namespace

bool parse_table(const std::string& src, Table* out, TableError* err) {
  Table t;
  std::vector<int> step_lines;
  text::Syntax syn;
  syn.motion_names = "DRV/DRVC/DRVZ";
  syn.motion = [&](const std::string& kw, const std::string& rest, size_t i) {
    if (kw != "DRV" && kw != "DRVC" && kw != "DRVZ") return false;
    if (i == SIZE_MAX) return true;
    Step& st = t.steps[i];
    if (kw == "DRVZ") {
      st.motion = Motion::Drvz;
      if (rest != "MD0" && rest != "MD1" && rest != "MD2") throw Fail{50, "DRVZ mode must be MD0, MD1 or MD2"};
      st.zero_mode = rest[2] - '0';
    } else {
      st.motion = kw == "DRV" ? Motion::Drv : Motion::Drvc;
      drive_operands(rest, &st);
    }
    return true;
  };
  if (!text::parse_program(src, syn, &t.steps, &step_lines, err)) return false;
  if (!check_table(t, err, step_lines)) return false;
  *out = std::move(t);
  return true;
}

bool check_table(const Table& t, TableError* err, const std::vector<int>& lines) {
  const auto fail = [&](size_t i, int code, const std::string& m) {
    *err = {code, i < lines.size() ? lines[i] : 0, "step " + std::to_string(i + 1) + ": " + m};
    return false;
  };
  int chain = 0, chain_dir = 0;
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    if (chain > 0) {
      if (s.motion == Motion::Drvz) return fail(i, 42, "DRVZ can't follow DRVC");
      if (s.abs) return fail(i, 41, "ABS positioning is not allowed within DRVC commands");
      if (s.dir != 0 && s.dir != chain_dir) return fail(i, 34, "a DRVC chain keeps the first DRVC's direction");
    }
    if (s.motion == Motion::Drvc) {
      if (chain == 0) {
        if (s.dir == 0) return fail(i, 34, "a DRVC direction must be + or -");
        chain_dir = s.dir;
      }
      if (++chain > 7) return fail(i, 34, "a DRVC chain has at most 8 speeds");
      if (s.transfer != Transfer::None || s.goto_kind != Step::Next)
        return fail(i, 34, "DRVC continues with the next step: only GOTO NEXT");
      if (i + 1 == t.steps.size()) return fail(i, 34, "a DRVC chain must end with DRV");
    } else {
      chain = 0;
    }
  }
  return true;
}

using text::op_text;

std::string format_table(const Table& t) {
  std::ostringstream o;
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    o << text::format_head(i, s);
    if (s.motion == Motion::Drvz) {
      o << "    DRVZ MD" << s.zero_mode << "\n";
    } else {
      o << "    " << (s.motion == Motion::Drv ? "DRV " : "DRVC ") << (s.abs ? "ABS" : "ADR") << ","
        << (s.dir > 0 ? "+" : s.dir < 0 ? "-" : " ") << "," << op_text(s.stroke) << "," << (s.ut ? "Ut" : "Ps") << "\n";
    }
    o << text::format_flow(s);
  }
  o << "MEND\n";
  return o.str();
}

bool homing_table(uint32_t speed, int mode, Table* out, TableError* err) {
  return parse_table("SPD " + std::to_string(speed) + "\nDRVZ MD" + std::to_string(mode) + "\nGOTO NEXT\nMEND\n", out, err);
}

}  // namespace motion
}  // namespace plc_cell
