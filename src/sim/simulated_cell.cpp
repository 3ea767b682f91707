#include "plc_cell/sim/simulated_cell.h"

#include <algorithm>

namespace plc_cell {

void SimulatedCell::drive(uint32_t x, std::unique_ptr<InputSignal> signal) {
  drivers_.push_back({x, std::move(signal)});
}

void SimulatedCell::release(uint32_t x) {
  drivers_.erase(std::remove_if(drivers_.begin(), drivers_.end(), [x](const Driver& d) { return d.x == x; }),
                 drivers_.end());
}

void SimulatedCell::before_inputs(uint64_t now_us) {
  for (auto& d : drivers_) {
    bool v = d.signal->level(now_us, mem_);
    if (!v && scanned_ && std::find(captured_.begin(), captured_.end(), d.x) != captured_.end())
      v = d.signal->on_between(last_us_, now_us);
    engine_.set_input(d.x, v);
  }
  scanned_ = true;
  last_us_ = now_us;
}

}  // namespace plc_cell
