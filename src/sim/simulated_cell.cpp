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
  for (auto& d : drivers_) engine_.set_input(d.x, d.signal->level(now_us, mem_));
}

}  // namespace plc_cell
