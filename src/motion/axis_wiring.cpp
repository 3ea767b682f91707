// The axes' pins in the Y image, and their wiring and encoders into the counters.
#include "plc_cell/motion/axis_wiring.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {
namespace motion {

void AxisWiring::attach() {
  for (int n = 0; n < kAxes; ++n) {
    const AxisDef& d = cfg_.axes[n];
    if (!d.used) continue;
    const Axis* ax = &axes_[n].axis;
    const auto attach = [&](const AxisSignal& sig, int a, int b, int line) {
      signals_.push_back(std::make_unique<AxisSignal>(sig));
      if (a < 0 && b < 0) return;
      if (!hsc_) throw SourceError::at(cfg_.file, line, 1, "axes.pso" + std::to_string(n) + ": no counters unit");
      try {
        hsc_->attach_source(signals_.back().get(), a, b);
      } catch (const SourceError&) {
        throw;
      } catch (const Error& e) {
        throw SourceError::at(cfg_.file, line, 1, "axes.pso" + std::to_string(n) + ": " + e.what());
      }
    };
    if (d.has_output) {
      attach(AxisSignal::pins(d.name + ".pins", ax, d.mode, d.polarity, d.stepspeed.used), d.wired[0], d.wired[1],
             d.wiring_line);
      pins_[n] = signals_.back().get();
      any_pins_ = true;
      if (hsc_) {  // the pulse generator drives these pins, not the Y relays
        hsc_->own_output(static_cast<uint32_t>(2 * n));
        hsc_->own_output(static_cast<uint32_t>(2 * n + 1));
      }
    } else if (d.wired[0] >= 0 || d.wired[1] >= 0) {
      throw SourceError::at(cfg_.file, d.wiring_line, 1,
                            "axes.pso" + std::to_string(n) + ".wiring: the pins carry pulses only with `output:`");
    }
    if (d.encoder.used)
      attach(AxisSignal::encoder(d.name + ".encoder", ax, d.encoder.periods), d.encoder.a, d.encoder.b, d.encoder.line);
  }
}

void AxisWiring::detach() {
  if (hsc_) {
    for (const auto& s : signals_) hsc_->detach_source(s.get());
    for (int n = 0; n < kAxes; ++n)
      if (pins_[n]) {
        hsc_->own_output(static_cast<uint32_t>(2 * n), false);
        hsc_->own_output(static_cast<uint32_t>(2 * n + 1), false);
      }
  }
  signals_.clear();
  pins_.fill(nullptr);
  any_pins_ = false;
}

void AxisWiring::write_owned_pins(uint64_t t) const {
  for (int n = 0; n < kAxes; ++n) {
    if (!pins_[n]) continue;
    const PinLevels l = pins_[n]->levels(t);
    mem_.set_bit(Area::Y, static_cast<uint32_t>(2 * n), l.first);
    mem_.set_bit(Area::Y, static_cast<uint32_t>(2 * n + 1), l.second);
  }
}

}  // namespace motion
}  // namespace plc_cell
