// The manual's text form of a FUN140 program: parse (line-precise errors with the
// manual's codes) and format.
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

#include "plc_cell/motion/params.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

bool Step::operator==(const Step& o) const {
  return speed == o.speed && motion == o.motion && abs == o.abs && dir == o.dir && stroke == o.stroke &&
         ut == o.ut && zero_mode == o.zero_mode && transfer == o.transfer && time == o.time &&
         contact_area == o.contact_area && contact == o.contact && goto_kind == o.goto_kind &&
         goto_value == o.goto_value;
}

namespace {

std::string upper(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return s;
}
std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}
bool parse_int(const std::string& s, int64_t* v) {
  if (s.empty() || s.size() > 12) return false;
  size_t i = (s[0] == '-' || s[0] == '+') ? 1 : 0;
  if (i == s.size()) return false;
  int64_t r = 0;
  for (; i < s.size(); ++i) {
    if (!std::isdigit(static_cast<unsigned char>(s[i]))) return false;
    r = r * 10 + (s[i] - '0');
  }
  *v = s[0] == '-' ? -r : r;
  return true;
}

struct Fail {
  int code;
  std::string msg;
};

// A register operand Rn / Dn; words = 2 for 32-bit values (the pair must fit).
bool reg_operand(const std::string& s, int words, Operand* op, std::string* why) {
  if (s.size() < 2 || (s[0] != 'R' && s[0] != 'D')) return false;
  int64_t n;
  if (!parse_int(s.substr(1), &n) || s[1] == '-' || s[1] == '+') {
    *why = "'" + s + "' is not a register";
    op->kind = Operand::R;
    op->value = -1;
    return true;
  }
  const int64_t top = s[0] == 'R' ? 8071 : 4095;
  op->kind = s[0] == 'R' ? Operand::R : Operand::D;
  op->value = (n < 0 || n + words - 1 > top) ? -1 : static_cast<int32_t>(n);
  if (op->value < 0) *why = s + ": register out of range";
  return true;
}

// Constant or Rn/Dn. Codes: bad register -> reg_code, bad constant -> val_code.
Operand value_operand(const std::string& s, int words, int64_t lo, int64_t hi, int reg_code, int val_code,
                      const char* what) {
  Operand op;
  std::string why;
  if (reg_operand(s, words, &op, &why)) {
    if (op.value < 0) throw Fail{reg_code, what + std::string(": ") + why};
    return op;
  }
  int64_t v;
  if (!parse_int(s, &v)) throw Fail{reg_code, std::string(what) + ": '" + s + "' is neither a constant nor Rn/Dn"};
  if (v < lo || v > hi)
    throw Fail{val_code, std::string(what) + " " + s + " out of range " + std::to_string(lo) + "~" + std::to_string(hi)};
  op.value = static_cast<int32_t>(v);
  return op;
}

void contact_operand(const std::string& s, Step* st) {
  static const struct { char c; ContactArea a; int top; } areas[] = {
      {'X', ContactArea::X, 255}, {'Y', ContactArea::Y, 255}, {'M', ContactArea::M, 1911}, {'S', ContactArea::S, 999}};
  int64_t n;
  for (const auto& a : areas)
    if (!s.empty() && s[0] == a.c && parse_int(s.substr(1), &n) && s[1] != '-' && s[1] != '+') {
      if (n < 0 || n > a.top) throw Fail{34, s + ": contact out of range (X0~X255, Y0~Y255, M0~M1911, S0~S999)"};
      st->contact_area = a.a;
      st->contact = static_cast<int>(n);
      return;
    }
  throw Fail{34, "'" + s + "' is not a contact (X, Y, M or S)"};
}

std::vector<std::string> split_commas(const std::string& s) {
  std::vector<std::string> out;
  std::string cur;
  for (char c : s) {
    if (c == ',') {
      out.push_back(trim(cur));
      cur.clear();
    } else {
      cur += c;
    }
  }
  out.push_back(trim(cur));
  return out;
}

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

Operand time_operand(const std::string& rest) {
  std::string r = trim(rest);
  std::vector<std::string> t = split_commas(r);
  if (t.size() == 2 && t[0] == "TIME") r = t[1];
  else if (t.size() != 1) throw Fail{34, "expected Time,<0.01 s> (e.g. Time,100)"};
  return value_operand(r, 1, 0, 65535, 34, 34, "time");
}

}  // namespace

bool parse_table(const std::string& text, Table* out, TableError* err) {
  Table t;
  std::vector<int> step_lines;
  enum { Start, HaveSpd, HaveMotion, HaveTransfer, Ended } state = Start;
  std::istringstream in(text);
  std::string raw;
  int line = 0;
  std::vector<int> goto_lines;
  try {
    while (std::getline(in, raw)) {
      ++line;
      auto c = raw.find(';');
      if (c != std::string::npos) raw.resize(c);
      c = raw.find("//");
      if (c != std::string::npos) raw.resize(c);
      std::string s = upper(trim(raw));
      if (s.empty()) continue;
      if (state == Ended) throw Fail{34, "text after MEND"};
      // Optional step number (001) before the command.
      size_t i = 0;
      while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
      if (i > 0) {
        const int n = std::stoi(s.substr(0, std::min<size_t>(i, 6)));
        s = trim(s.substr(i));
        if (!s.empty() && s[0] == ':') s = trim(s.substr(1));
        const int expect = static_cast<int>(t.steps.size()) + (s.rfind("SPD", 0) == 0 ? 1 : 0);
        if (n != expect) throw Fail{34, "step number " + std::to_string(n) + " where step " + std::to_string(expect) + " is"};
        if (s.empty()) continue;
      }
      const auto sp = s.find_first_of(" \t");
      const std::string kw = s.substr(0, sp);
      const std::string rest = sp == std::string::npos ? "" : trim(s.substr(sp));
      if (kw == "MEND") {
        if (state != Start) throw Fail{34, "MEND inside a step (a step ends with GOTO)"};
        if (!rest.empty()) throw Fail{34, "MEND takes no operand"};
        state = Ended;
      } else if (kw == "SPD") {
        if (state != Start) throw Fail{34, "SPD before the previous step's GOTO"};
        if (static_cast<int>(t.steps.size()) == kMaxSteps) throw Fail{36, "more than 250 steps"};
        t.steps.emplace_back();
        step_lines.push_back(line);
        t.steps.back().speed = value_operand(rest, 2, 1, kMaxHz, 30, 31, "speed");
        state = HaveSpd;
      } else if (kw == "DRV" || kw == "DRVC" || kw == "DRVZ") {
        if (state != HaveSpd) throw Fail{34, kw + " must follow SPD"};
        Step& st = t.steps.back();
        if (kw == "DRVZ") {
          st.motion = Motion::Drvz;
          if (rest != "MD0" && rest != "MD1" && rest != "MD2") throw Fail{50, "DRVZ mode must be MD0, MD1 or MD2"};
          st.zero_mode = rest[2] - '0';
        } else {
          st.motion = kw == "DRV" ? Motion::Drv : Motion::Drvc;
          drive_operands(rest, &st);
        }
        state = HaveMotion;
      } else if (kw == "WAIT" || kw == "ACT" || kw == "EXT") {
        if (state != HaveMotion) throw Fail{34, kw + " must follow the step's DRV/DRVC/DRVZ"};
        Step& st = t.steps.back();
        if (kw == "EXT") {
          st.transfer = Transfer::Ext;
          contact_operand(rest, &st);
        } else if (kw == "ACT") {
          st.transfer = Transfer::Act;
          st.time = time_operand(rest);
        } else if (rest.rfind("TIME", 0) == 0) {
          st.transfer = Transfer::WaitTime;
          st.time = time_operand(rest);
        } else {
          st.transfer = Transfer::WaitContact;
          contact_operand(rest, &st);
        }
        state = HaveTransfer;
      } else if (kw == "GOTO") {
        if (state != HaveMotion && state != HaveTransfer) throw Fail{34, "GOTO must follow the step's motion or transfer"};
        Step& st = t.steps.back();
        int64_t n;
        Operand op;
        std::string why;
        if (rest == "NEXT") {
          st.goto_kind = Step::Next;
        } else if (reg_operand(rest, 1, &op, &why)) {
          if (op.value < 0) throw Fail{34, "GOTO " + why};
          st.goto_kind = op.kind == Operand::R ? Step::R : Step::D;
          st.goto_value = op.value;
        } else if (parse_int(rest, &n) && n >= 1 && n <= kMaxSteps) {
          st.goto_kind = Step::Number;
          st.goto_value = static_cast<int>(n);
          goto_lines.push_back(line);
        } else {
          throw Fail{34, "GOTO needs NEXT, a step number 1~N, Rn or Dn"};
        }
        state = Start;
      } else {
        throw Fail{34, "unknown command '" + kw + "'"};
      }
    }
    if (state != Ended) throw Fail{34, state == Start ? "missing MEND" : "step not ended by GOTO"};
    if (t.steps.empty()) {
      line = 0;
      throw Fail{35, "no steps"};
    }
  } catch (const Fail& f) {
    *err = {f.code, line, f.msg};
    if (f.msg == "missing MEND" || f.msg == "step not ended by GOTO") err->line = line + 1;
    return false;
  }
  // GOTO constants must name an existing step.
  size_t gi = 0;
  for (const auto& st : t.steps)
    if (st.goto_kind == Step::Number) {
      if (st.goto_value > static_cast<int>(t.steps.size())) {
        *err = {34, goto_lines[gi], "GOTO " + std::to_string(st.goto_value) + ": there are only " +
                                       std::to_string(t.steps.size()) + " steps"};
        return false;
      }
      ++gi;
    }
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

namespace {
std::string op_text(const Operand& o) {
  if (o.kind == Operand::R) return "R" + std::to_string(o.value);
  if (o.kind == Operand::D) return "D" + std::to_string(o.value);
  return std::to_string(o.value);
}
const char* contact_prefix(ContactArea a) { return a == ContactArea::X ? "X" : a == ContactArea::Y ? "Y" : a == ContactArea::M ? "M" : "S"; }
}  // namespace

std::string format_table(const Table& t) {
  std::ostringstream o;
  char num[24];
  for (size_t i = 0; i < t.steps.size(); ++i) {
    const Step& s = t.steps[i];
    std::snprintf(num, sizeof num, "%03zu", i + 1);
    o << num << " SPD " << op_text(s.speed) << "\n";
    if (s.motion == Motion::Drvz) {
      o << "    DRVZ MD" << s.zero_mode << "\n";
    } else {
      o << "    " << (s.motion == Motion::Drv ? "DRV " : "DRVC ") << (s.abs ? "ABS" : "ADR") << ","
        << (s.dir > 0 ? "+" : s.dir < 0 ? "-" : " ") << "," << op_text(s.stroke) << "," << (s.ut ? "Ut" : "Ps") << "\n";
    }
    switch (s.transfer) {
      case Transfer::WaitTime: o << "    WAIT Time," << op_text(s.time) << "\n"; break;
      case Transfer::Act: o << "    ACT Time," << op_text(s.time) << "\n"; break;
      case Transfer::WaitContact: o << "    WAIT " << contact_prefix(s.contact_area) << s.contact << "\n"; break;
      case Transfer::Ext: o << "    EXT " << contact_prefix(s.contact_area) << s.contact << "\n"; break;
      case Transfer::None: break;
    }
    o << "    GOTO ";
    if (s.goto_kind == Step::Next) o << "NEXT";
    else if (s.goto_kind == Step::Number) o << s.goto_value;
    else o << (s.goto_kind == Step::R ? "R" : "D") << s.goto_value;
    o << "\n";
  }
  o << "MEND\n";
  return o.str();
}

}  // namespace motion
}  // namespace plc_cell
