// Differential fuzzer (docs/native-engine.md): a random valid program over the whole
// instruction set (contacts and edge contacts, nested blocks, coils, SET/RST, timers with
// constant and register presets, counters, FUN with .P/.D, with flags and with several
// inputs, in word forms and handlers, JMP, CALL/RTS, FOR/NEXT, an interrupt routine) runs on the interpreter and on the native engine, each on its own memory, with
// the same random inputs, forced points and interrupts, for up to 200 scans. Any
// difference between the two memories, or between their faults, is a finding.
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>

#include "plc_cell/core/error.h"

#include "../core/see3_function.h"
#include "../core/two_engines.h"

using namespace plc_cell;

namespace {

class Generator {
 public:
  explicit Generator(FuzzedDataProvider& f) : f_(f) {}

  std::string program() {
    const int nets = f_.ConsumeIntegralInRange(1, 14);
    int labels = 0;
    for (int n = 0; n < nets; ++n) {
      if (f_.ConsumeIntegralInRange(0, 5) == 0) {
        out_ += "FOR " + std::to_string(f_.ConsumeIntegralInRange(0, 4)) + "\n";
        network(2, labels, nets);
        out_ += "NEXT\n";
      } else {
        network(2, labels, nets);
      }
      if (pending_label_ > labels && f_.ConsumeBool()) out_ += "LBL L" + std::to_string(labels++) + "\n";
    }
    while (labels < pending_label_) out_ += "LBL L" + std::to_string(labels++) + "\n";
    out_ += "END\n";
    for (int s = 0; s < 2; ++s) {  // S0 may call S1, never the other way: no recursion
      out_ += "LBL S" + std::to_string(s) + "\n";
      network(s == 0 ? 1 : 0, labels, 0);
      out_ += "RTS\n";
    }
    out_ += "LBL X0+I\n";
    network(0, labels, 0);
    out_ += "RTI\n";
    return out_;
  }

 private:
  std::string bit(const char* areas) {
    const std::string a(1, areas[f_.ConsumeIntegralInRange<size_t>(0, std::strlen(areas) - 1)]);
    if (a == "T" || a == "C") return a + number(a[0]);
    return a + std::to_string(f_.ConsumeIntegralInRange(0, a == "X" ? 15 : 11));
  }
  // Timers of the three time bases; counters of 16 and of 32 bits.
  std::string number(char area) {
    static const int timers[] = {0, 1, 60, 210}, counters[] = {0, 1, 200, 201};
    const int k = f_.ConsumeIntegralInRange(0, 3);
    return std::to_string(area == 'T' ? timers[k] : counters[k]);
  }
  std::string contact(const char* op) {
    static const char* const mods[] = {"", "NOT ", "TU ", "TD "};
    return std::string(op) + " " + mods[f_.ConsumeIntegralInRange(0, 3)] + bit("XYMTC") + "\n";
  }
  void block(int depth) {  // a contact expression; leaves the stack as it found it
    const int n = f_.ConsumeIntegralInRange(0, 6);
    for (int k = 0; k < n; ++k) {
      const int what = f_.ConsumeIntegralInRange(0, 5);
      if (what <= 1) out_ += contact("AND");
      else if (what <= 3) out_ += contact("OR");
      else if (depth < 12) {
        out_ += contact("LD");
        block(depth + 1);
        out_ += f_.ConsumeBool() ? "ANDLD\n" : "ORLD\n";
      }
    }
  }
  std::string reg() { return (f_.ConsumeBool() ? "R" : "D") + std::to_string(f_.ConsumeIntegralInRange(0, 7)); }
  std::string mods() {
    std::string m = f_.ConsumeBool() ? ".D" : "";
    if (f_.ConsumeBool()) m += m.empty() ? ".P" : "P";
    return m;
  }
  // SUB or CMP with some of their flags (on points that may be forced), Sb a register, a
  // small constant or one beyond int16 (which the word forms leave to the handler).
  std::string flag_fun() {
    const bool cmp = f_.ConsumeBool();
    const int v = f_.ConsumeIntegralInRange(0, 2);
    std::string s = std::string(cmp ? "CMP" : "SUB") + mods() + " Sa=" + reg() +
                    " Sb=" + (v == 0 ? reg() : v == 1 ? std::to_string(f_.ConsumeIntegralInRange(-3, 3)) : "40000");
    if (!cmp) s += " D=" + reg();
    static const char* const flags[2][3] = {{"ZR", "CY", "BR"}, {"EQ", "GT", "LT"}};
    for (const char* flag : flags[cmp])
      if (f_.ConsumeBool()) s += std::string(" ") + flag + "=" + bit("YM");
    return s + "\n";
  }
  void output(int calls, int& labels, int nets) {
    switch (f_.ConsumeIntegralInRange(0, 13)) {
      case 0: out_ += "OUT " + bit("YM") + "\n"; break;
      case 1: out_ += "OUT NOT " + bit("YM") + "\n"; break;
      case 2: out_ += "SET " + bit("YM") + "\n"; break;
      case 3: out_ += "RST " + bit("YMTC") + "\n"; break;
      case 4: out_ += "RST " + reg() + "\n"; break;
      case 5:  // a constant preset, or a register's (which the program's INC/ADD/MOV change)
        out_ += "TMR T" + number('T') + " " +
                (f_.ConsumeBool() ? std::to_string(f_.ConsumeIntegralInRange(0, 30)) : reg()) + "\n";
        break;
      case 6: out_ += "CTR C" + number('C') + " " +
                      std::to_string(f_.ConsumeIntegralInRange(0, 9)) + "\n"; break;
      case 7: out_ += "INC" + mods() + " " + reg() + "\n"; break;
      case 8: out_ += "ADD" + mods() + " Sa=" + reg() + " Sb=" + std::to_string(f_.ConsumeIntegralInRange(-9, 9)) +
                      " D=" + reg() + "\n"; break;
      case 9: out_ += "MOV" + mods() + " S=WX0 D=" + reg() + "\n"; break;
      case 10:
        if (nets > 0) {  // main only: a forward jump; the LBLs come after later networks
          out_ += "JMP L" + std::to_string(labels + f_.ConsumeIntegralInRange(0, 1)) + "\n";
          pending_label_ = std::max(pending_label_, labels + 2);
        }
        break;
      case 11:
        if (calls > 0) out_ += "CALL S" + std::to_string(2 - calls + f_.ConsumeIntegralInRange(0, calls - 1)) + "\n";
        break;
      case 12: out_ += flag_fun(); break;
      default: out_ += "MOV S=" + std::to_string(f_.ConsumeIntegralInRange(0, 99)) + " D=" + reg() + "\n"; break;
    }
  }
  void network(int calls, int& labels, int nets) {
    out_ += contact("ORG");
    block(0);
    if (f_.ConsumeIntegralInRange(0, 7) == 0) {  // a three-input FUN takes two LD blocks
      for (int k = 0; k < 2; ++k) {
        out_ += contact("LD");
        block(1 + k);
      }
      out_ += "SEE3" + std::string(f_.ConsumeBool() ? ".P" : "") + " D=" + reg() + "\n";
    }
    const int outs = f_.ConsumeIntegralInRange(1, 3);
    for (int k = 0; k < outs; ++k) {
      output(calls, labels, nets);
      if (f_.ConsumeBool()) out_ += contact(f_.ConsumeBool() ? "AND" : "OR");
    }
  }

  FuzzedDataProvider& f_;
  std::string out_;
  int pending_label_ = 0;
};

[[noreturn]] void finding(const std::string& what, const std::string& text) {
  std::fprintf(stderr, "%s\n--- program ---\n%s", what.c_str(), text.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider f(data, size);
  const std::string text = Generator(f).program();
  std::optional<native_test::TwoEngines> e;
  try {
    e.emplace(native_test::see3_table(), text, "gen.il");
  } catch (const Error& err) {
    finding(std::string("the generator wrote an invalid program: ") + err.what(), text);
  }
  if (!e->native.native_active()) finding(e->native.engine_status(), text);
  const int scans = f.ConsumeIntegralInRange(1, 200);
  for (int s = 1; s <= scans && f.remaining_bytes() > 0; ++s) {
    e->set_inputs(f.ConsumeIntegral<uint16_t>());
    const int forced = f.ConsumeIntegralInRange(-1, 15);  // a point forced (disabled) or released, or none
    const bool disable = f.ConsumeBool();
    if (forced >= 0)
      for (Memory* m : {&e->mem_i, &e->mem_n})
        m->set_disabled(forced < 8 ? Area::Y : Area::M, static_cast<uint32_t>(forced) % 8, disable);
    const uint32_t dt = f.ConsumeIntegralInRange<uint32_t>(0, 40000);
    const bool irq = f.ConsumeIntegralInRange(0, 3) == 0;
    bool ok = true;
    const std::string d = e->step(dt, irq, (irq ? "routine X0+I in scan " : "scan ") + std::to_string(s), &ok);
    if (!d.empty()) finding(d, text);
    if (!ok) break;
  }
  return 0;
}
