#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "../cell_part.h"

namespace plc_cell_fuzz {
namespace {

// The counters, their inputs and the interrupts (docs/counters-and-interrupts.md): every
// mode and decoding, pulse measurement, edge interrupts driven by simulated edges,
// capture, filters and the time-base interrupts.
struct CountersPart {
  explicit CountersPart(CellDraft& draft)
      : d(draft), f(draft.f), pins(draft.pins), counters(draft.section("counters")), init(draft.init), body(draft.body) {}
  CellDraft& d;
  Fdp& f;
  Pins& pins;
  std::ostringstream &counters, &init, &body;
  std::vector<int> counting_inputs;  // what pulse measurement may measure

  void counter(int n) {
    if (n < 4) {
      if (d.claims.count("HHSC" + std::to_string(n))) return;
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
      d.labels.push_back("HSC" + std::to_string(n) + "I");
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
      d.labels.push_back("HSC" + std::to_string(n) + "I");
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
    d.labels.push_back("HSC" + std::to_string(n) + "I");
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
      d.labels.push_back("X" + std::to_string(x) + (up ? "+I" : "-I"));
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
      const bool pso0_wired = std::any_of(d.out.wired.begin(), d.out.wired.end(), [](const WiredAxis& w) { return w.ps == 0; });
      counters << "  filters: {";
      if (!pso0_wired) counters << "X0-X3: " << pick(f, fast) << ", ";
      counters << "X16-X23: " << pick(f, slow) << "}\n";
    }
    if (chance(f, 3)) counters << "  frequency_window: " << f.ConsumeIntegralInRange<int>(1, 1000) << "ms\n";
    static const char* const tb[] = {"1MSI", "2MSI", "3MSI", "4MSI", "5MSI", "10MSI", "50MSI", "100MSI", "HSTAI"};
    for (int i = f.ConsumeIntegralInRange<int>(0, 2); i > 0; --i) d.labels.push_back(pick(f, tb));
  }

  void generate() {
    for (int n = 0; n < 8; ++n)
      if (chance(f, 3)) counter(n);
    pulse_measurement();
    interrupts_and_edges();
    if (!sources.str().empty()) counters << "  sources:\n" << sources.str();
    if (!edges.str().empty()) counters << "  edges:\n" << edges.str();
  }
};

const RegisterCellPart registered({"counters", 20, [](CellDraft& d) { CountersPart(d).generate(); }});

}  // namespace
}  // namespace plc_cell_fuzz
