#include "plc_cell/temp/hspwm.h"

#include <algorithm>
#include <array>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/scan_engine.h"

namespace plc_cell {
namespace temp {
namespace {

using R = OperandRole;
// The generators live beside the PLC, like the hardware beside the CPU: its scan engine
// keeps them, so they go with it and a new PLC starts with none running.
struct Generators {
  std::array<HsPwmChannel, kHsPwmOutputs> channels{};
};

}  // namespace

double hspwm_frequency_hz(int pn, int rs) { return 18.432e6 / ((pn + 1) * (rs == 1 ? 1000.0 : 100.0)); }

HsPwmChannel hspwm_channel(const ScanEngine& engine, int pw) {
  const Generators* g = engine.extensions().get<Generators>();
  if (!g || pw < 0 || pw >= kHsPwmOutputs) return {};
  return g->channels[static_cast<size_t>(pw)];
}

void hspwm_reset(ScanEngine& engine) { engine.extensions().reset<Generators>(); }

void add_hspwm_function(FunctionTable& t) {
  FunctionSpec s;
  s.number = 139;
  s.mnemonic = "HSPWM";
  s.operands = {{"Pw", R::Const}, {"Op", R::Const}, {"Rs", R::Const},
                {"Pn", R::Source}, {"OR", R::Source}, {"WR", R::Register, false, 2}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // EN off stops the output
  s.check = [](const std::vector<Operand>& ops) -> std::string {
    if (ops.at(0).k < 0 || ops.at(0).k >= kHsPwmOutputs) return "Pw must be 0..3 (Y0, Y2, Y4, Y6)";
    if (ops.at(1).k != 0 && ops.at(1).k != 1) return "Op must be 0 or 1";
    if (ops.at(2).k != 0 && ops.at(2).k != 1) return "Rs must be 0 (1/100) or 1 (1/1000)";
    return {};
  };
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    const int steps = o[2].k == 1 ? 1000 : 100;
    const int pn = static_cast<int>(std::clamp<int64_t>(c.get(o[3]), 0, 255));
    const int width = static_cast<int>(std::clamp<int64_t>(c.get(o[4]), 0, steps));
    HsPwmChannel ch;
    ch.running = c.en;
    if (c.en) {
      // Op 1 inverts: width 0 is full output (manual: 0 -> 10 V, 1000 -> 0 V).
      ch.duty = double(o[1].k == 1 ? steps - width : width) / steps;
      ch.frequency_hz = hspwm_frequency_hz(pn, static_cast<int>(o[2].k));
    }
    // WR (plc_cell's layout; the manual only says it must not be shared): the width
    // being generated and the Pn in use, 0 while stopped.
    o[5].w[0] = static_cast<uint16_t>(c.en ? width : 0);
    o[5].w[1] = static_cast<uint16_t>(c.en ? pn : 0);
    if (c.engine) c.engine->extensions().owned<Generators>().channels[static_cast<size_t>(o[0].k)] = ch;
  };
  t.add(s);
}

}  // namespace temp
}  // namespace plc_cell
