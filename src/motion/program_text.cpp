// The step skeleton and operands shared by the FUN140 and FUN147 text forms, and
// the register encoding of a step's flow part (see program_text.h).
#include "program_text.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <sstream>

#include "plc_cell/motion/params.h"

namespace plc_cell {
namespace motion {
namespace text {

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

std::string op_text(const Operand& o) {
  if (o.kind == Operand::R) return "R" + std::to_string(o.value);
  if (o.kind == Operand::D) return "D" + std::to_string(o.value);
  return std::to_string(o.value);
}

namespace {

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

Operand time_operand(const std::string& rest) {
  std::string r = trim(rest);
  std::vector<std::string> t = split_commas(r);
  if (t.size() == 2 && t[0] == "TIME") r = t[1];
  else if (t.size() != 1) throw Fail{34, "expected Time,<0.01 s> (e.g. Time,100)"};
  return value_operand(r, 1, 0, 65535, 34, 34, "time");
}

const char* contact_prefix(ContactArea a) { return a == ContactArea::X ? "X" : a == ContactArea::Y ? "Y" : a == ContactArea::M ? "M" : "S"; }

}  // namespace

namespace {

enum class State { Start, HaveSpd, HaveMotion, HaveTransfer, Ended };

// The steps of a program text, command by command.
struct StepReader {
  const Syntax& syn;
  std::vector<Step>& t;
  std::vector<int>* step_lines;
  std::vector<int> goto_lines;
  int line = 0;
  State state = State::Start;

  void command(const std::string& kw, const std::string& rest);
  void transfer(const std::string& kw, const std::string& rest);
  void go_to(const std::string& rest);
};

void StepReader::command(const std::string& kw, const std::string& rest) {
  if (const int code = syn.reject ? syn.reject(kw) : 0) throw Fail{code, kw + " is not allowed in this program"};
  if (kw == "MEND") {
    if (state != State::Start) throw Fail{34, "MEND inside a step (a step ends with GOTO)"};
    if (!rest.empty()) throw Fail{34, "MEND takes no operand"};
    state = State::Ended;
  } else if (kw == "SPD") {
    if (state != State::Start) throw Fail{34, "SPD before the previous step's GOTO"};
    if (static_cast<int>(t.size()) == kMaxSteps) throw Fail{36, "more than 250 steps"};
    t.emplace_back();
    step_lines->push_back(line);
    t.back().speed = value_operand(rest, 2, 1, kMaxHz, 30, 31, "speed");
    state = State::HaveSpd;
  } else if (kw == "WAIT" || kw == "ACT" || kw == "EXT") {
    transfer(kw, rest);
  } else if (kw == "GOTO") {
    go_to(rest);
  } else if (state == State::HaveSpd && syn.motion(kw, rest, t.size() - 1)) {
    state = State::HaveMotion;
  } else if (syn.motion(kw, "", SIZE_MAX)) {  // a motion command out of place
    throw Fail{34, kw + " must follow SPD"};
  } else {
    throw Fail{34, "unknown command '" + kw + "'"};
  }
}

void StepReader::transfer(const std::string& kw, const std::string& rest) {
  if (state != State::HaveMotion) throw Fail{34, kw + " must follow the step's " + syn.motion_names};
  Step& st = t.back();
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
  state = State::HaveTransfer;
}

void StepReader::go_to(const std::string& rest) {
  if (state != State::HaveMotion && state != State::HaveTransfer)
    throw Fail{34, "GOTO must follow the step's motion or transfer"};
  Step& st = t.back();
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
  state = State::Start;
}

// Takes an optional step number (001, 001:) off the front of s and checks it against
// the steps read so far; false when nothing follows it.
bool strip_step_number(std::string* s, size_t steps) {
  size_t i = 0;
  while (i < s->size() && std::isdigit(static_cast<unsigned char>((*s)[i]))) ++i;
  if (i == 0) return true;
  const int n = std::stoi(s->substr(0, std::min<size_t>(i, 6)));
  *s = trim(s->substr(i));
  if (!s->empty() && (*s)[0] == ':') *s = trim(s->substr(1));
  const int expect = static_cast<int>(steps) + (s->rfind("SPD", 0) == 0 ? 1 : 0);
  if (n != expect) throw Fail{34, "step number " + std::to_string(n) + " where step " + std::to_string(expect) + " is"};
  return !s->empty();
}

// GOTO constants must name an existing step.
bool check_gotos(const std::vector<Step>& t, const std::vector<int>& goto_lines, TableError* err) {
  size_t gi = 0;
  for (const auto& st : t)
    if (st.goto_kind == Step::Number) {
      if (st.goto_value > static_cast<int>(t.size())) {
        *err = {34, goto_lines[gi], "GOTO " + std::to_string(st.goto_value) + ": there are only " +
                                       std::to_string(t.size()) + " steps"};
        return false;
      }
      ++gi;
    }
  return true;
}

}  // namespace

bool parse_program(const std::string& text, const Syntax& syn, std::vector<Step>* steps,
                   std::vector<int>* step_lines, TableError* err) {
  StepReader r{syn, *steps, step_lines, {}};
  std::istringstream in(text);
  std::string raw;
  try {
    while (std::getline(in, raw)) {
      ++r.line;
      auto c = raw.find(';');
      if (c != std::string::npos) raw.resize(c);
      c = raw.find("//");
      if (c != std::string::npos) raw.resize(c);
      std::string s = upper(trim(raw));
      if (s.empty()) continue;
      if (r.state == State::Ended) throw Fail{34, "text after MEND"};
      if (!strip_step_number(&s, steps->size())) continue;
      const auto sp = s.find_first_of(" \t");
      r.command(s.substr(0, sp), sp == std::string::npos ? "" : trim(s.substr(sp)));
    }
    if (r.state != State::Ended) throw Fail{34, r.state == State::Start ? "missing MEND" : "step not ended by GOTO"};
    if (steps->empty()) {
      r.line = 0;
      throw Fail{35, "no steps"};
    }
  } catch (const Fail& f) {
    *err = {f.code, r.line, f.msg};
    if (f.msg == "missing MEND" || f.msg == "step not ended by GOTO") err->line = r.line + 1;
    return false;
  }
  return check_gotos(*steps, r.goto_lines, err);
}

std::string format_head(size_t index, const Step& s) {
  char num[24];
  std::snprintf(num, sizeof num, "%03zu", index + 1);
  return std::string(num) + " SPD " + op_text(s.speed) + "\n";
}

std::string format_flow(const Step& s) {
  std::ostringstream o;
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
  return o.str();
}

bool decode_header(const uint16_t* r, size_t n, uint16_t magic, int step_words, int* steps, TableError* err) {
  char m[8];
  std::snprintf(m, sizeof m, "%04XH", magic);
  if (n < kHeaderWords || r[1] != magic) {
    *err = {34, 0, std::string("no program of this instruction at SR (SR+1 must be ") + m + ")"};
    return false;
  }
  *steps = r[0];
  if (*steps < 1 || *steps > kMaxSteps) {
    *err = {*steps > kMaxSteps ? 36 : 35, 0, "SR+0 (number of steps) must be 1~250, is " + std::to_string(*steps)};
    return false;
  }
  if (kHeaderWords + size_t(step_words) * *steps > n) {
    *err = {35, 0, std::to_string(*steps) + " steps do not fit in the register area"};
    return false;
  }
  return true;
}

namespace {
constexpr int kTransferShift = 8;  // 3 bits: Transfer
constexpr int kGotoShift = 11;     // 2 bits: NEXT, number, R, D
constexpr int kAreaShift = 13;     // 2 bits: X, Y, M, S
uint32_t field(uint16_t w, int shift, int bits) { return (w >> shift) & ((1u << bits) - 1); }
bool is_contact(Transfer t) { return t == Transfer::WaitContact || t == Transfer::Ext; }
}  // namespace

uint16_t flow_bits(const Step& s) {
  return static_cast<uint16_t>((uint32_t(s.transfer) << kTransferShift) | (uint32_t(s.goto_kind) << kGotoShift) |
                               (uint32_t(s.contact_area) << kAreaShift));
}

uint16_t flow_time_word(const Step& s) {
  return static_cast<uint16_t>(is_contact(s.transfer) ? s.contact : s.time.value);
}

bool decode_flow(uint16_t cmd, uint16_t time_word, uint16_t goto_word, uint32_t tk, int steps, Step* s,
                 std::string* why) {
  const uint32_t tr = field(cmd, kTransferShift, 3);
  if (tr > 4) return *why = "bad transfer condition", false;
  if (cmd & 0x8000u) return *why = "bit 15 of the command word must be 0", false;
  s->transfer = static_cast<Transfer>(tr);
  s->goto_kind = static_cast<Step::GotoKind>(field(cmd, kGotoShift, 2));
  s->contact_area = static_cast<ContactArea>(field(cmd, kAreaShift, 2));
  if (is_contact(s->transfer)) s->contact = time_word;
  else if (s->transfer != Transfer::None) s->time = {static_cast<Operand::Kind>(tk), time_word};
  s->goto_value = s->goto_kind == Step::Next ? 0 : goto_word;
  if (s->goto_kind == Step::Number && (s->goto_value < 1 || s->goto_value > steps))
    return *why = "GOTO beyond the last step", false;
  return true;
}

}  // namespace text
}  // namespace motion
}  // namespace plc_cell
