#include "cell_generator.h"

#include <algorithm>
#include <sstream>

namespace plc_cell_fuzz {
namespace {

using Fdp = FuzzedDataProvider;

template <class T, size_t N>
const T& pick(Fdp& f, const T (&a)[N]) {
  return a[f.ConsumeIntegralInRange<size_t>(0, N - 1)];
}

bool chance(Fdp& f, int one_in) { return f.ConsumeIntegralInRange<int>(1, one_in) == 1; }

std::string hex(uint32_t v) {
  std::ostringstream o;
  o << "0x" << std::hex << std::uppercase << v;
  return o.str();
}

// X0-X15 are the high-speed inputs (counters, interrupts, DOG, PG0, wiring); a pin is
// taken once so that most cells are accepted. Rarely a taken pin is handed out again:
// the builder must then refuse the cell with a message.
struct Pins {
  bool used[48] = {};
  int take(Fdp& f, int lo, int hi) {
    if (chance(f, 64)) return f.ConsumeIntegralInRange<int>(lo, hi);
    for (int tries = 0; tries < 8; ++tries) {
      const int x = f.ConsumeIntegralInRange<int>(lo, hi);
      if (!used[x]) {
        used[x] = true;
        return x;
      }
    }
    return -1;
  }
  bool claim(int x) {
    if (used[x]) return false;
    used[x] = true;
    return true;
  }
};

struct Builder {
  Fdp& f;
  Pins pins;
  std::ostringstream counters, axes, modules, sim, init, body, isr;
  std::vector<std::string> labels;  // interrupt routines to write after END
  bool hhsc_taken[4] = {};
  std::vector<int> counting_inputs;  // what pulse measurement may measure
  GeneratedCell out;

  explicit Builder(Fdp& fdp) : f(fdp) {}

  // ---- axes (FUN140/141, docs: motion) ------------------------------------------
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
    hhsc_taken[ps] = true;
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
    sim << "    X" << abt << ": {pulse: {period: " << period / 1000.0 << ", width: " << width / 1000.0 << ", delay: " << ms() << "}}\n";
    body << "ORG M1925\nMPARA Ps=" << ps << " SR=R" << 2000 + 30 * ps << " ERR=M" << 40 + ps << "\n"
         << "ORG M" << (chance(f, 4) ? 702 : 1925) << "\nLD X" << pau << "\nLD X" << abt << "\nHSPSO Ps=" << ps
         << " SR=R" << 300 * ps << " WR=R" << 1200 + 10 * ps << " ACT=M" << 50 + ps << " ERR=M" << 54 + ps
         << " DN=M" << 58 + ps << "\n";
    if (chance(f, 4)) body << "ORG X" << abt << "\nFUN 142 PSOFF N=" << ps << "\n";
    if (chance(f, 4)) body << "ORG M1925\nFUN 143 PSCNV Ps=" << ps << " D=R" << 1300 + 2 * ps << "\n";
  }

  std::string ms() { return std::to_string(f.ConsumeIntegralInRange<int>(0, 3000) / 1000.0); }

  static std::string indent(const std::string& text, int n) {
    std::string o, pad(n, ' ');
    std::istringstream in(text);
    for (std::string l; std::getline(in, l);) o += pad + l + "\n";
    return o;
  }

  // ---- counters and interrupts (docs: counters-and-interrupts) ------------------------
  void counter(int n) {
    if (n < 4) {
      if (hhsc_taken[n]) return;
      if (chance(f, 4)) {
        counters << "  hsc" << n << ": {type: timer}\n";
        return;
      }
      const int mode = f.ConsumeIntegralInRange<int>(0, 7);
      if (!pins.claim(4 * n)) return;
      counters << "  hsc" << n << ": {mode: MD" << mode;
      counting_inputs.push_back(4 * n);
      bool has_b = false;
      if ((mode >= 4 || f.ConsumeBool()) && pins.claim(4 * n + 1)) {
        counters << ", b: true";
        counting_inputs.push_back(4 * n + 1);
        has_b = true;
      }
      decoding(mode == 4 && has_b);
      if (chance(f, 3) && pins.claim(4 * n + 2)) counters << ", mask: true";
      if (chance(f, 3) && pins.claim(4 * n + 3)) counters << ", clear: true";
      if (chance(f, 3)) {
        static const char* const inv[] = {"[count]", "[mask]", "[clear]", "[count, mask, clear]"};
        counters << ", invert: " << pick(f, inv);
      }
      counters << "}\n";
      init << "FUN 8D MOV S=" << f.ConsumeIntegralInRange<int>(-100000, 100000) << " D=DR" << 4098 + 4 * n << "\n"
           << "FUN 93 HSCTW CN=" << n << " D=1\n";
      body << "ORG M1925\nFUN 92 HSCTR CN=" << n << "\n";
      source_on(4 * n, mode >= 6);
      labels.push_back("HSC" + std::to_string(n) + "I");
      return;
    }
    static const int modes[] = {0, 2, 4};
    const int mode = pick(f, modes);
    if (mode == 4) {  // A/B: A even, B the next input
      const int a = 2 * f.ConsumeIntegralInRange<int>(0, 7);
      if (!pins.claim(a) || !pins.claim(a + 1)) return;
      counters << "  hsc" << n << ": {mode: MD4, a: X" << a << ", b: X" << a + 1;
      counting_inputs.push_back(a);
      counting_inputs.push_back(a + 1);
      decoding(true);
      counters << "}\n";
      source_on(a, true);
      labels.push_back("HSC" + std::to_string(n) + "I");
      return;
    }
    const int a = pins.take(f, 0, 15);
    if (a < 0) return;
    counters << "  hsc" << n << ": {mode: MD" << mode << ", a: X" << a;
    counting_inputs.push_back(a);
    if (mode != 0 || f.ConsumeBool()) {
      const int b = pins.take(f, 0, 15);
      if (b >= 0) {
        counters << ", b: X" << b;
        counting_inputs.push_back(b);
      }
    }
    decoding(false);
    counters << "}\n";
    source_on(a, false);
    labels.push_back("HSC" + std::to_string(n) + "I");
  }

  // The TRi decodings belong on an A/B counter in MD4; now and then elsewhere, which
  // the cell must refuse with a message (rare: not what an exhausted input yields).
  void decoding(bool ab) {
    if (!(ab ? chance(f, 2) : f.ConsumeIntegralInRange<int>(0, 63) == 63)) return;
    static const char* const kinds[] = {"simple", "enhanced", "x1", "x2", "x4"};
    counters << ", decoding: " << pick(f, kinds);
  }

  // Pulse measurement on some counting inputs (now and then any input: refused unless
  // it is one).
  void pulse_measurement() {
    if (counting_inputs.empty() || !chance(f, 2)) return;
    std::string list;
    for (int x : counting_inputs)
      if (f.ConsumeBool()) list += (list.empty() ? "X" : ", X") + std::to_string(x);
    if (list.empty() || f.ConsumeIntegralInRange<int>(0, 31) == 31) list += (list.empty() ? "X" : ", X") + std::to_string(f.ConsumeIntegralInRange<int>(0, 15));
    static const char* const units[] = {"us", "0.1us"};
    static const char* const timeouts[] = {"auto", "3ms", "50ms", "1s"};
    counters << "  pulse_measurement: {inputs: [" << list << "], unit: " << pick(f, units) << ", timeout: " << pick(f, timeouts) << "}\n";
  }

  std::ostringstream sources, edges;
  int source_count = 0;
  void source_on(int a, bool encoder) {
    if (!chance(f, 2)) return;
    sources << "    - {name: src" << source_count++ << ", " << (encoder ? "type: encoder, " : "type: pulses, ") << "a: X" << a
            << ", hz: " << f.ConsumeIntegralInRange<int>(-20000, 20000) << "}\n";
  }

  void interrupts_and_edges() {
    std::string list;
    for (int i = f.ConsumeIntegralInRange<int>(0, 3); i > 0; --i) {
      const int x = pins.take(f, 0, 15);
      if (x < 0) continue;
      const bool up = f.ConsumeBool();
      list += std::string(list.empty() ? "" : ", ") + "X" + std::to_string(x) + (up ? "+" : "-");
      labels.push_back("X" + std::to_string(x) + (up ? "+I" : "-I"));
      int t[3];
      for (int& v : t) v = f.ConsumeIntegralInRange<int>(0, 3000);
      std::sort(t, t + 3);
      edges << "    - {x: X" << x << ", steps: [[" << t[0] / 1000.0 << ", 1], [" << t[1] / 1000.0 << ", 0], ["
            << t[2] / 1000.0 << ", 1]]}\n";
    }
    if (!list.empty()) counters << "  interrupts: [" << list << "]\n";
    if (chance(f, 3)) counters << "  capture: [X" << f.ConsumeIntegralInRange<int>(0, 35) << "]\n";
    if (chance(f, 3)) {
      static const char* const fast[] = {"14kHz", "28kHz", "56kHz", "112kHz", "225kHz", "450kHz", "900kHz", "1.8MHz"};
      static const char* const slow[] = {"1ms", "2ms", "5ms", "10ms", "15ms"};
      // A filter slower than a wired axis' pulse rate drops pulses, as on the PLC: the
      // wired check needs the pins unfiltered, so PSO0's X0-X3 are filtered only when free.
      const bool pso0_wired = std::any_of(out.wired.begin(), out.wired.end(), [](const WiredAxis& w) { return w.ps == 0; });
      counters << "  filters: {";
      if (!pso0_wired) counters << "X0-X3: " << pick(f, fast) << ", ";
      counters << "X16-X23: " << pick(f, slow) << "}\n";
    }
    if (chance(f, 3)) counters << "  frequency_window: " << f.ConsumeIntegralInRange<int>(1, 1000) << "ms\n";
    static const char* const tb[] = {"1MSI", "2MSI", "3MSI", "4MSI", "5MSI", "10MSI", "50MSI", "100MSI", "HSTAI"};
    for (int i = f.ConsumeIntegralInRange<int>(0, 2); i > 0; --i) labels.push_back(pick(f, tb));
  }

  // ---- modules and PID (docs: analog-and-temperature) ---------------------------------
  void temperature() {
    static const char* const types[] = {"2TC", "6TC", "16TC", "6RTD", "16RTD", "6NTC", "2A4TC", "2A4RTD"};
    static const char* const tcs[] = {"J", "K", "E", "T", "R", "S", "B", "N"};
    static const char* const rtds[] = {"PT100", "PT1000"};
    static const char* const r25s[] = {"2000", "5000", "10000", "20000"};
    modules << "  temperature:\n    scan: " << (f.ConsumeBool() ? "normal" : "fast") << "\n    unit: "
            << (f.ConsumeBool() ? "C" : "F") << "\n    averaging: " << (1 << f.ConsumeIntegralInRange<int>(0, 3))
            << "\n    readings: R0\n    working: D0\n    modules:\n";
    const bool plant = f.ConsumeBool();
    for (int m = f.ConsumeIntegralInRange<int>(1, 3); m > 0; --m) {
      const std::string type = pick(f, types);
      modules << "      - type: " << type << "\n";
      if (type.find("TC") != std::string::npos)
        modules << "        sensor: " << pick(f, tcs) << "\n        cold_junction: " << f.ConsumeIntegralInRange<int>(-20, 60) << "\n";
      else if (type.find("RTD") != std::string::npos)
        modules << "        sensor: " << pick(f, rtds) << "\n        alpha: " << (f.ConsumeBool() ? "DIN" : "JIS") << "\n";
      else
        modules << "        r25: " << pick(f, r25s) << "\n        beta: " << f.ConsumeIntegralInRange<int>(2000, 5000) << "\n";
      modules << "        channels:\n";
      for (int c = f.ConsumeIntegralInRange<int>(1, 3); c > 0; --c) {
        switch (f.ConsumeIntegralInRange<int>(0, 4)) {
          case 0: modules << "          - {temperature: " << f.ConsumeIntegralInRange<int>(-300, 2000) << "}\n"; break;
          case 1: {
            static const char* const tc_units[] = {" mV", " C", ""};
            static const char* const r_units[] = {" ohm", " kohm", " C", ""};
            const bool tc = type.find("TC") != std::string::npos;
            modules << "          - {value: " << f.ConsumeIntegralInRange<int>(tc ? -100 : 1, 4000) / 10.0
                    << (tc ? pick(f, tc_units) : pick(f, r_units)) << "}\n";
            break;
          }
          case 2: modules << "          - {open: true}\n"; break;
          case 3: if (plant) { modules << "          - {plant: oven}\n"; break; } [[fallthrough]];
          default: modules << "          - {}\n"; break;
        }
      }
    }
    if (plant)
      modules << "  plants:\n    - {name: oven, ambient: 25, initial: " << f.ConsumeIntegralInRange<int>(0, 300)
              << ", gain: " << f.ConsumeIntegralInRange<int>(1, 1000) << ", time_constant: "
              << f.ConsumeIntegralInRange<int>(1, 600) << ", dead_time: " << f.ConsumeIntegralInRange<int>(0, 20)
              << ", heater: Y12}\n";
    // FUN86 TPCTL on a random point with random loop settings (the oven example's shape).
    init << "MOV S=" << f.ConsumeIntegralInRange<int>(0, 3000) << " D=R100\nMOV S=" << f.ConsumeIntegralInRange<int>(0, 100)
         << " D=R110\nMOV S=" << f.ConsumeIntegralInRange<int>(0, 500) << " D=R120\nMOV S="
         << f.ConsumeIntegralInRange<int>(0, 500) << " D=R130\nMOV S=" << f.ConsumeIntegralInRange<int>(0, 500) << " D=R140\n";
    body << "ORG M1925\nLD M" << (f.ConsumeBool() ? 1925 : 703) << "\nFUN 86 Md=" << f.ConsumeIntegralInRange<int>(0, 3)
         << " Yn=Y12 Sn=" << f.ConsumeIntegralInRange<int>(0, 40) << " Zn=" << f.ConsumeIntegralInRange<int>(0, 4)
         << " Sv=R100 Os=R110 PR=R120 IR=R130 DR=R140 OR=R200 WR=R300 ERR=M100 ALM=M101\n";
  }

  void analog() {
    static const char* const types[] = {"6AD", "4A2D", "4DA", "2DA"};
    static const char* const pol[] = {"bipolar", "unipolar"};
    modules << "  analog:\n    modules:\n";
    for (int m = f.ConsumeIntegralInRange<int>(1, 2); m > 0; --m) {
      const std::string type = pick(f, types);
      modules << "      - type: " << type << "\n        code: " << pick(f, pol) << "\n        signal: " << pick(f, pol)
              << "\n        span: " << (f.ConsumeBool() ? 10 : 5) << "\n";
      if (type.find("DA") != std::string::npos && chance(f, 2)) {
        modules << "        outputs:\n";
        for (int c = f.ConsumeIntegralInRange<int>(1, 2); c > 0; --c)
          modules << "          - {current: " << (f.ConsumeBool() ? "true" : "false") << conditioning(false) << "}\n";
      }
      if (type.find("AD") == std::string::npos) continue;  // 4DA, 2DA: outputs only
      modules << "        inputs:\n";
      for (int c = f.ConsumeIntegralInRange<int>(1, 3); c > 0; --c) {
        static const char* const units[] = {" V", " mA", ""};
        modules << "          - {value: " << f.ConsumeIntegralInRange<int>(-300, 300) / 10.0 << pick(f, units)
                << conditioning(true) << "}\n";
      }
    }
    // FUN30 PID on the first input (manual A:7376): SR, PR and WR as the manual's tables.
    for (int i = 0; i < 15; ++i)
      init << "MOV S=" << f.ConsumeIntegralInRange<int>(-100, 20000) << " D=R" << 400 + i << "\n";
    body << "ORG M1925\nLD M" << (f.ConsumeBool() ? 704 : 1925) << "\nLD M705\n"
         << "FUN 30 Ts=R399 SR=R400 OR=R420 PR=R408 WR=R430 ERR=M110 HAL=M111 LAL=M112\n";
  }

  // The TRi's ADC/DAC conditioning, mostly within its ranges (N 1-9, offset -100..100).
  std::string conditioning(bool input) {
    if (!chance(f, 2)) return "";
    const bool wide = chance(f, 8);
    std::ostringstream o;
    o << ", conditioning: {";
    if (input) o << "average: " << f.ConsumeIntegralInRange<int>(wide ? 0 : 1, wide ? 12 : 9) << ", ";
    o << "gain: " << f.ConsumeIntegralInRange<int>(wide ? -20000 : -9999, wide ? 20000 : 9999)
      << ", offset: " << f.ConsumeIntegralInRange<int>(wide ? -300 : -100, wide ? 300 : 100) << "}";
    return o.str();
  }

  // ---- FUN150/151 on ports nobody answers --------------------------------------------
  void protocol() {
    static const char* const fatek_ports[] = {"tcp:127.0.0.1:9", "tcp:127.0.0.1:1"};
    modules_ << "fatek:\n  timeout_ms: " << f.ConsumeIntegralInRange<int>(10, 100) << "\n  ports:\n    1: " << pick(f, fatek_ports)
             << "\nmodbus:\n  ports:\n    2: {tcp: 127.0.0.1:9}\n";
    for (int i = 0; i < 16; ++i) init << "MOV S=" << f.ConsumeIntegralInRange<int>(0, 0xFFFF) << " D=R" << 1500 + i << "\n";
    body << "ORG M1925\nLD M706\nLD M707\nFUN 151 Pt=1 MD=" << f.ConsumeIntegralInRange<int>(0, 2)
         << " SR=R1500 WR=R1540 ACT=M120 ERR=M121 DN=M122\n"
         << "ORG M1925\nLD M708\nLD M709\nFUN 150 Pt=2 SR=R1500 WR=R1560 ACT=M123 ERR=M124 DN=M125\n";
  }
  std::ostringstream modules_;  // top-level fatek:/modbus:

  void build() {
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
        labels.push_back("PSO" + std::to_string(ps) + "I");
    }
    for (int n = 0; n < 8; ++n)
      if (chance(f, 3)) counter(n);
    pulse_measurement();
    interrupts_and_edges();
    if (chance(f, 3)) temperature();
    if (chance(f, 3)) analog();
    if (chance(f, 4)) protocol();
    // EN/DIS of random interrupts from the ladder.
    for (const std::string& l : labels) {
      if (l.find("MSI") != std::string::npos || l == "HSTAI" || !chance(f, 6)) continue;  // time bases: R4162
      const bool en = f.ConsumeBool();
      body << "ORG M" << (f.ConsumeBool() ? 1925 : 710) << "\nFUN 14" << (en ? "5 EN" : "6 DIS") << " LBL=" << l << "\n";
    }

    std::ostringstream y;
    y << "cell:\n  name: generated\n";
    static const int scans_ms[] = {1, 2, 5};
    const uint64_t scan_ms = static_cast<uint64_t>(pick(f, scans_ms));
    out.scan_us = scan_ms * 1000;
    out.span_us = out.scan_us * f.ConsumeIntegralInRange<uint64_t>(50, 300);
    y << "plc:\n  scan_period: " << scan_ms / 1000.0 << "\n";
    if (!counters.str().empty() || !sources.str().empty() || !edges.str().empty()) {
      y << "counters:\n" << counters.str();
      if (!sources.str().empty()) y << "  sources:\n" << sources.str();
      if (!edges.str().empty()) y << "  edges:\n" << edges.str();
    }
    if (!axes.str().empty()) y << "axes:\n" << axes.str();
    if (!modules.str().empty()) y << "modules:\n" << modules.str();
    y << modules_.str();
    if (!sim.str().empty()) y << "simulation:\n  inputs:\n" << sim.str();
    out.yaml = y.str();

    std::ostringstream il;
    il << "ORG M1924\n" << init.str() << body.str() << "END\n";
    std::sort(labels.begin(), labels.end());
    labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
    int r = 600;
    for (const std::string& l : labels) il << "LBL " << l << "\nORG M1925\nINC D=R" << r++ << "\nRTI\n";
    out.il = il.str();
  }
};

}  // namespace

GeneratedCell generate_cell(FuzzedDataProvider& fdp) {
  Builder b(fdp);
  b.build();
  return b.out;
}

}  // namespace plc_cell_fuzz
