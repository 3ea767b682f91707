#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "../cell_part.h"

namespace plc_cell_fuzz {
namespace {

// The pulse axes (FUN140/141, docs/motion.md). Some axes are "wired": output UD, pins
// looped back to the HHSC of the same number in MD0, and moves nothing cuts; the
// generator records what the manual promises for them (cell_invariants.h). The others
// are drawn over every FUN141 field, their tables over every step form.
struct AxesPart {
  explicit AxesPart(CellDraft& draft)
      : d(draft), f(draft.f), pins(draft.pins), counters(draft.section("counters")), axes(draft.section("axes")),
        sim(draft.sim), body(draft.body), out(draft.out) {}
  CellDraft& d;
  Fdp& f;
  Pins& pins;
  std::ostringstream &counters, &axes, &sim, &body;
  GeneratedCell& out;

  struct Step {
    std::string text;
    bool drvz = false;
    bool abs = false;
    int64_t stroke = 0;  // signed pulses (ADR) or the target (ABS)
  };

  // A step the wired check can follow: DRV with Ps strokes and nothing that cuts it.
  Step wired_step(int k, int max_speed, bool homing_first) {
    Step s;
    std::ostringstream t;
    t << (k < 10 ? "00" : "0") << k << " SPD " << f.ConsumeIntegralInRange<int>(100, max_speed) << "\n";
    if (k == 1 && homing_first) {
      s.drvz = true;
      t << "    DRVZ MD" << f.ConsumeIntegralInRange<int>(0, 2) << "\n";
    } else if (chance(f, 4)) {
      s.abs = true;
      s.stroke = f.ConsumeIntegralInRange<int64_t>(-20000, 20000);
      t << "    DRV ABS,," << s.stroke << ",Ps\n";
    } else {
      const int64_t n = f.ConsumeIntegralInRange<int64_t>(1, 20000);
      const bool minus = f.ConsumeBool();
      s.stroke = minus ? -n : n;
      t << "    DRV ADR," << (minus ? "-" : "+") << "," << n << ",Ps\n";
    }
    if (chance(f, 3)) t << "    WAIT Time," << f.ConsumeIntegralInRange<int>(0, 30) << "\n";
    t << "    GOTO NEXT\n";
    s.text = t.str();
    return s;
  }

  // Any step the text form allows; with `anything`, also what it refuses (codes 30-50).
  std::string wild_step(int k, int steps, bool anything) {
    std::ostringstream t;
    t << (k < 10 ? "00" : "0") << k << " SPD ";
    switch (f.ConsumeIntegralInRange<int>(0, 5)) {
      case 0: t << "R" << f.ConsumeIntegralInRange<int>(900, 910); break;
      case 1: t << "D" << f.ConsumeIntegralInRange<int>(0, 4) << "0"; break;
      case 2: t << f.ConsumeIntegralInRange<int>(anything ? 0 : 1, anything ? 1000000 : 921600); break;
      default: t << f.ConsumeIntegralInRange<int>(1, 200000); break;
    }
    t << "\n    ";
    static const char* const motion[] = {"DRV", "DRV", "DRVC", "DRVZ"};
    std::string m = pick(f, motion);
    if (m == "DRVC" && !anything) m = "DRV";  // chain rules: only in the anything tables
    static const char* const res[] = {"Ut", "Ps"};
    if (m == "DRVZ") {
      t << "DRVZ MD" << f.ConsumeIntegralInRange<int>(0, anything ? 3 : 2) << "\n";
    } else if (anything) {
      static const char* const coord[] = {"ADR", "ABS"};
      static const char* const dir[] = {"+", "-", ""};
      t << m << " " << pick(f, coord) << "," << pick(f, dir) << ",";
      if (chance(f, 5)) t << "R" << f.ConsumeIntegralInRange<int>(900, 910);
      else t << f.ConsumeIntegralInRange<int64_t>(-100000, 100000);
      t << "," << pick(f, res) << "\n";
    } else if (f.ConsumeBool()) {
      t << "DRV ABS,," << f.ConsumeIntegralInRange<int64_t>(-100000, 100000) << "," << pick(f, res) << "\n";
    } else {
      t << "DRV ADR," << (f.ConsumeBool() ? "+" : "-") << ",";
      if (chance(f, 5)) t << "R" << f.ConsumeIntegralInRange<int>(900, 910);
      else t << f.ConsumeIntegralInRange<int64_t>(0, 100000);
      t << "," << pick(f, res) << "\n";
    }
    switch (f.ConsumeIntegralInRange<int>(0, 6)) {
      case 0: t << "    WAIT Time," << f.ConsumeIntegralInRange<int>(0, 50) << "\n"; break;
      case 1: t << "    WAIT X" << f.ConsumeIntegralInRange<int>(0, 47) << "\n"; break;
      case 2: t << "    ACT Time," << f.ConsumeIntegralInRange<int>(0, 50) << "\n"; break;
      case 3: t << "    EXT X" << f.ConsumeIntegralInRange<int>(0, 47) << "\n"; break;
      default: break;
    }
    if (chance(f, 4)) t << "    GOTO " << f.ConsumeIntegralInRange<int>(1, anything ? steps + 1 : steps) << "\n";
    else t << "    GOTO NEXT\n";
    return t.str();
  }

  void wired_axis(int ps) {
    WiredAxis w;
    w.ps = ps;
    const int u = 4 * ps, dog = 4 * ps + 2, pg0 = 4 * ps + 3;
    pins.claim(u);
    pins.claim(u + 1);
    d.claims.insert("HHSC" + std::to_string(ps));
    counters << "  hsc" << ps << ": {mode: MD0, b: true, name: wired" << ps << "}\n";
    const int p4 = f.ConsumeIntegralInRange<int>(1000, 200000);
    w.homes = chance(f, 2);
    uint32_t p15 = 0xFFFFFFFFu;
    std::ostringstream sw;
    if (w.homes) {
      const uint32_t dog_b = chance(f, 8) ? 0xFF : static_cast<uint32_t>(dog);
      const uint32_t lim_b = chance(f, 3) ? 0xFF : static_cast<uint32_t>(0x80 | (24 + ps));
      const uint32_t pg0_b = chance(f, 6) ? 0xFF : static_cast<uint32_t>(pg0 | (f.ConsumeBool() ? 0x80 : 0));
      const uint32_t clr_b = chance(f, 2) ? 0xFF : static_cast<uint32_t>(8 + ps);
      p15 = dog_b | lim_b << 8 | pg0_b << 16 | clr_b << 24;
      pins.claim(dog);
      pins.claim(pg0);
      // Started before, on or beyond the DOG (homing toward decreasing positions, P9-1 = 1).
      const int w_dog = f.ConsumeIntegralInRange<int>(50, 3000);
      const int gap = f.ConsumeIntegralInRange<int>(50, 5000);
      int from = 0;
      switch (f.ConsumeIntegralInRange<int>(0, 2)) {
        case 0: from = -gap - w_dog; break;  // before (home side)
        case 1: from = -w_dog / 2; break;    // on
        default: from = gap; break;          // beyond: between the DOG and the limit
      }
      const int limit = std::min(from, 0) - f.ConsumeIntegralInRange<int>(100, 8000);
      sw << "    switches:\n"
         << "      - {x: X" << dog << ", from: " << from << ", to: " << from + w_dog << "}\n"
         << "      - {x: X" << 24 + ps << ", from: " << limit + 1 << "}\n"
         << "      - {x: X" << pg0 << ", period: " << f.ConsumeIntegralInRange<int>(20, 500)
         << ", width: " << f.ConsumeIntegralInRange<int>(1, 10) << "}\n";
    }
    axes << "  pso" << ps << ":\n    name: wired_axis" << ps << "\n    output: UD\n"
         << "    polarity: " << (f.ConsumeBool() ? "normal_off" : "normal_on") << "\n"
         << "    wiring: {Y" << 2 * ps << ": X" << u << ", Y" << 2 * ps + 1 << ": X" << u + 1 << "}\n"
         << sw.str()
         << "    params: {at: R" << 2000 + 30 * ps << ", p4: " << p4
         << ", p5: " << f.ConsumeIntegralInRange<int>(0, 1000)
         << ", p6: " << f.ConsumeIntegralInRange<int>(1, 2000)
         << ", p8: " << f.ConsumeIntegralInRange<int>(0, 300)
         << ", p9: 0x0100, p12: " << f.ConsumeIntegralInRange<int>(0, 300)
         << ", p15: " << hex(p15) << ", p16: " << f.ConsumeIntegralInRange<int>(-1000, 1000)
         << ", p17: " << f.ConsumeIntegralInRange<int>(0, 20) << "}\n";
    const int steps = f.ConsumeIntegralInRange<int>(1, 6);
    w.stroke.assign(steps + 1, 0);
    w.checked.assign(steps + 1, false);
    w.absolute.assign(steps + 1, false);
    std::string table;
    for (int k = 1; k <= steps; ++k) {
      const Step s = wired_step(k, std::min(p4, 100000), w.homes);
      table += s.text;
      w.checked[k] = !s.drvz;
      w.stroke[k] = s.stroke;
      w.absolute[k] = s.abs;
    }
    table += "MEND\n";
    axes << "    table:\n      at: R" << 300 * ps << "\n      text: |\n" << indent(table, 8);
    body << "ORG M1925\nMPARA Ps=" << ps << " SR=R" << 2000 + 30 * ps << " ERR=M" << 40 + ps << "\n"
         << "ORG M1925\nLD M700\nLD M701\nHSPSO Ps=" << ps << " SR=R" << 300 * ps << " WR=R" << 1200 + 10 * ps
         << " ACT=M" << 50 + ps << " ERR=M" << 54 + ps << " DN=M" << 58 + ps << "\n";
    out.wired.push_back(w);
  }

  void wild_axis(int ps) {
    static const char* const outputs[] = {"UD", "PR", "AB", ""};
    const std::string output = pick(f, outputs);
    axes << "  pso" << ps << ":\n";
    if (!output.empty()) {
      axes << "    output: " << output << "\n    polarity: " << (f.ConsumeBool() ? "normal_off" : "normal_on") << "\n";
      if (chance(f, 2)) {
        const int a = pins.take(f, 0, 15), b = pins.take(f, 0, 15);
        if (a >= 0 && b >= 0) axes << "    wiring: {Y" << 2 * ps << ": X" << a << ", Y" << 2 * ps + 1 << ": X" << b << "}\n";
      }
      if (chance(f, 3)) {
        const int a = pins.take(f, 0, 15), b = pins.take(f, 0, 15);
        if (a >= 0 && b >= 0)
          axes << "    encoder: {a: X" << a << ", b: X" << b << ", periods_per_pulse: " << f.ConsumeIntegralInRange<int>(1, 4) << "}\n";
      }
    }
    static const char* const types[] = {"linear", "rotary"};
    axes << "    type: " << pick(f, types) << "\n    units_per_pulse: 0.001\n";
    if (chance(f, 2)) {
      axes << "    switches:\n";
      for (int i = f.ConsumeIntegralInRange<int>(1, 3); i > 0; --i) {
        const int x = pins.take(f, 0, 47);
        if (x < 0) continue;
        const int lo = f.ConsumeIntegralInRange<int>(-20000, 20000), len = f.ConsumeIntegralInRange<int>(0, 20000);
        if (f.ConsumeBool())
          axes << "      - {x: X" << x << ", from: " << lo << ", to: " << lo + len << "}\n";
        else
          axes << "      - {x: X" << x << ", period: " << len % 1000 + 2 << ", width: " << 1 + len % (len % 1000 + 1) << "}\n";
      }
    }
    // Every parameter drawn over and beyond its range; P15's four fields FFH or a pin.
    // Mostly within the FUN141 ranges (so the cell runs), one cell in six anywhere.
    const bool out_of_range = chance(f, 6);
    auto in = [&](int lo, int hi, int wide_hi) { return f.ConsumeIntegralInRange<int>(lo, out_of_range ? wide_hi : hi); };
    auto field = [&](int lo, int hi) { return chance(f, 3) ? 0xFFu : static_cast<uint32_t>(f.ConsumeIntegralInRange<int>(lo, hi)); };
    const uint32_t p15 = field(0, 47) | field(0, 0xFF) << 8 | field(0, 0xFF) << 16 | field(0, 31) << 24;
    // The TRi step-count ramp replaces P4, P5, P8 and P12 on a P/R axis; one in
    // sixteen keeps a conflicting parameter (refused).
    const bool stepspeed = (output == "PR" || output.empty()) && chance(f, 3);
    const bool conflict = stepspeed && chance(f, 16);
    if (stepspeed)
      axes << "    stepspeed: {pps: " << in(1, 10000, 20000) << ", accel_steps: " << in(1, 5000, 3000000)
           << ", done: M" << 800 + ps << "}\n";
    const int p0 = in(0, 2, 3);  // machine/compound units: P4 is cm/min, kept small enough to stay <= 921.6 kHz
    axes << "    params: {at: R" << 2000 + 30 * ps << ", p0: " << p0 << ", p1: " << in(1, 2000, 65535)
         << ", p2: " << in(1000, 999999, 1000000) << ", p3: " << in(0, 3, 4);
    if (!stepspeed || conflict) axes << ", p4: " << in(1, p0 == 1 ? 153000 : 100, 1000000) << ", p5: " << in(0, 15300, 20000);
    axes << ", p6: " << in(1, 15300, 65535) << ", p7: " << in(0, 32767, 40000);
    if (!stepspeed) axes << ", p8: " << in(0, 30000, 31000);
    axes << ", p9: " << hex((f.ConsumeBool() ? 0x0100u : 0u) | (f.ConsumeBool() ? 1u : 0u)) << ", p10: "
         << f.ConsumeIntegralInRange<int>(-32768, 32767) << ", p11: " << f.ConsumeIntegralInRange<int>(-32768, 32767);
    if (!stepspeed) axes << ", p12: " << in(0, 30000, 31000);
    axes << ", p13: " << in(0, 30000, 31000) << ", p14: " << in(0, 1999999, 2000000)
         << ", p15: " << hex(p15) << ", p16: " << f.ConsumeIntegralInRange<int>(-100000, 100000)
         << ", p17: " << in(0, 255, 300) << "}\n";
    const int steps = f.ConsumeIntegralInRange<int>(1, 8);
    std::string table;
    const bool anything = chance(f, 6);
    for (int k = 1; k <= steps; ++k) table += wild_step(k, steps, anything);
    table += "MEND\n";
    axes << "    table:\n      at: R" << 300 * ps << "\n      text: |\n" << indent(table, 8);
    // PAU and ABT from simulated inputs, so pauses and aborts land mid-move.
    const int pau = 30 + 2 * ps, abt = 31 + 2 * ps;
    const int on = f.ConsumeIntegralInRange<int>(0, 3000), off = f.ConsumeIntegralInRange<int>(on, 4000);
    sim << "    X" << pau << ": {steps: [[" << on / 1000.0 << ", 1], [" << off / 1000.0 << ", 0]]}\n";
    const int period = f.ConsumeIntegralInRange<int>(2, 3000), width = f.ConsumeIntegralInRange<int>(1, period - 1);
    sim << "    X" << abt << ": {pulse: {period: " << period / 1000.0 << ", width: " << width / 1000.0 << ", delay: " << seconds(f) << "}}\n";
    body << "ORG M1925\nMPARA Ps=" << ps << " SR=R" << 2000 + 30 * ps << " ERR=M" << 40 + ps << "\n"
         << "ORG M" << (chance(f, 4) ? 702 : 1925) << "\nLD X" << pau << "\nLD X" << abt << "\nHSPSO Ps=" << ps
         << " SR=R" << 300 * ps << " WR=R" << 1200 + 10 * ps << " ACT=M" << 50 + ps << " ERR=M" << 54 + ps
         << " DN=M" << 58 + ps << "\n";
    if (chance(f, 4)) body << "ORG X" << abt << "\nFUN 142 PSOFF N=" << ps << "\n";
    if (chance(f, 4)) body << "ORG M1925\nFUN 143 PSCNV Ps=" << ps << " D=R" << 1300 + 2 * ps << "\n";
  }


  void generate() {
    int kind[4];
    for (int ps = 0; ps < 4; ++ps) {
      kind[ps] = f.ConsumeIntegralInRange<int>(0, 3);
      if (kind[ps] == 1 || kind[ps] == 2)  // wired: its pins, DOG and PG0 before anyone else takes them
        for (int i = 0; i < 4; ++i) pins.used[4 * ps + i] = true;
    }
    for (int ps = 0; ps < 4; ++ps) {
      switch (kind[ps]) {
        case 1: case 2: wired_axis(ps); break;
        case 3: wild_axis(ps); break;
        default: break;
      }
      if (!out.wired.empty() && out.wired.back().ps == ps)
        d.labels.push_back("PSO" + std::to_string(ps) + "I");
    }
  }
};

const RegisterCellPart registered({"axes", 10, [](CellDraft& d) { AxesPart(d).generate(); }});

}  // namespace
}  // namespace plc_cell_fuzz
