#include "plc_cell/sim/apply_config.h"

#include <memory>

#include "plc_cell/core/plc.h"
#include "plc_cell/sim/simulated_cell.h"

namespace plc_cell {

void apply_cell_config(const CellConfig& cfg, Plc& plc, SimulatedCell& sim) {
  plc.locked([&](ScanEngine& e, Memory&) {
    e.set_retentive(cfg.retentive);
    e.set_watchdog_us(cfg.watchdog_us);
    // Lockstep's twin is a whole second cell, which whoever builds two makes
    // (run_in_lockstep, as the Cell of runtime/cell.h does): until then, the native engine.
    e.set_engine(cfg.engine == EngineChoice::Lockstep ? EngineChoice::Native : cfg.engine);
    for (const auto& tb : cfg.timer_bases)
      for (uint32_t t = tb.first; t <= tb.last; ++t) e.interpreter().set_timer_base(t, tb.base_us);
    return 0;
  });
  for (const auto& d : cfg.sim_inputs) {
    std::unique_ptr<InputSignal> s;
    switch (d.kind) {
      case SimInputDef::Kind::Pulse: s = std::make_unique<PulseSignal>(d.period_us, d.width_us, d.delay_us); break;
      case SimInputDef::Kind::Steps: s = std::make_unique<StepSignal>(d.steps); break;
      case SimInputDef::Kind::Follow:
        s = std::make_unique<FollowSignal>(d.source, d.on_delay_us, d.off_delay_us, d.invert);
        break;
    }
    sim.drive(d.x, std::move(s));
  }
}

}  // namespace plc_cell
