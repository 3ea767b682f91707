#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "../cell_part.h"

namespace plc_cell_fuzz {
namespace {

// The analog and temperature modules with their PID loops (docs/analog-and-temperature.md):
// every module type and sensor, open and simulated channels, a thermal plant, FUN86 and FUN30.
struct ModulesPart {
  explicit ModulesPart(CellDraft& draft)
      : f(draft.f), modules(draft.section("modules")), init(draft.init), body(draft.body) {}
  Fdp& f;
  std::ostringstream &modules, &init, &body;

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

  void generate() {
    if (chance(f, 3)) temperature();
    if (chance(f, 3)) analog();
  }
};

const RegisterCellPart registered({"modules", 30, [](CellDraft& d) { ModulesPart(d).generate(); }});

}  // namespace
}  // namespace plc_cell_fuzz
