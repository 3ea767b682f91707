#include "cell_invariants.h"

#include <cstdio>
#include <cstdlib>

#include "plc_cell/core/area.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell_fuzz {
namespace {

[[noreturn]] void violated(const char* what, int ps, int step, long long expected, long long got) {
  std::fprintf(stderr, "INVARIANT VIOLATED: %s: PSO%d step %d: expected %lld, got %lld\n", what, ps, step, expected, got);
  std::abort();
}

}  // namespace

WiredAxisCheck::WiredAxisCheck(plc_cell::SoftCell& cell, const std::vector<WiredAxis>& axes) : cell_(cell), axes_(axes) {
  cell_.plc().locked([&](plc_cell::ScanEngine&, plc_cell::Memory&) {
    cell_.get<plc_cell::motion::MotionUnit>()->on_step_done([this](int ps, int step, uint64_t t_ns) { step_done(ps, step, t_ns); });
    return 0;
  });
}

// Manual, FUN140: a DRV step outputs its stroke (ADR: relative, ABS: to the coordinate);
// nothing in a wired cell cuts a move, so each completed step lands exactly there.
void WiredAxisCheck::step_done(int ps, int step, uint64_t t_ns) {
  for (const WiredAxis& w : axes_) {
    if (w.ps != ps) continue;
    const int64_t pos = cell_.get<plc_cell::motion::MotionUnit>()->axis(ps).position(t_ns);
    if (step > 0 && static_cast<size_t>(step) < w.stroke.size() && w.checked[step]) {
      ++steps_checked_;
      if (w.absolute[step]) {
        if (pos != w.stroke[step]) violated("ABS step ends at its coordinate", ps, step, w.stroke[step], pos);
      } else if (pos - baseline_[ps] != w.stroke[step]) {
        violated("ADR step moves exactly its stroke", ps, step, w.stroke[step], pos - baseline_[ps]);
      }
    }
    baseline_[ps] = pos;
  }
}

void WiredAxisCheck::check_at_rest() {
  cell_.plc().locked([&](plc_cell::ScanEngine&, plc_cell::Memory& m) {
    for (const WiredAxis& w : axes_) {
      const int ps = w.ps;
      auto& mu = *cell_.get<plc_cell::motion::MotionUnit>();
      if (mu.busy(ps) || mu.frequency(ps) != 0.0) continue;
      const int64_t pos = mu.position(ps);
      const uint32_t dr = m.reg(plc_cell::Area::R, 4088 + 2 * ps) | static_cast<uint32_t>(m.reg(plc_cell::Area::R, 4089 + 2 * ps)) << 16;
      if (static_cast<int32_t>(dr) != pos) violated("DR4088+2Ps holds the position at rest", ps, 0, pos, static_cast<int32_t>(dr));
      if (w.homes) continue;
      const uint32_t cv = static_cast<uint32_t>(cell_.get<plc_cell::hsc::HscUnit>()->count(ps));
      if (cv != static_cast<uint32_t>(pos)) violated("the HSC on the pins counts every pulse", ps, 0, pos, static_cast<int32_t>(cv));
    }
    return 0;
  });
}

}  // namespace plc_cell_fuzz
