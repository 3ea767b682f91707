#include "plc_cell/sim/simulated_cell.h"

#include <algorithm>

#include "plc_cell/hsc/hsc_unit.h"

namespace plc_cell {

void SimulatedCell::drive(uint32_t x, std::unique_ptr<InputSignal> signal) {
  drivers_.push_back({x, std::move(signal)});
}

void SimulatedCell::drop(uint32_t x) {
  drivers_.erase(std::remove_if(drivers_.begin(), drivers_.end(), [x](const Driver& d) { return d.x == x; }),
                 drivers_.end());
}

bool SimulatedCell::exact(uint32_t x) const { return exact_ && x < 16 && !exact_->source_on(int(x)); }

void SimulatedCell::schedule_edge(uint32_t x, uint64_t t_ns, bool level) {
  if (exact(x)) exact_->schedule_edge(int(x), t_ns, level);
}

void SimulatedCell::override_input(uint32_t x) {
  overridden_.set(x);
  ++overrides_;
  for (auto& d : drivers_)
    if (d.x == x) d.overridden = true;
  if (exact_ && x < 16) exact_->mute_simulation(int(x), true);
}

bool SimulatedCell::resume(uint32_t x) {
  overridden_.reset(x);
  ++overrides_;
  bool any = false;
  for (auto& d : drivers_)
    if (d.x == x) {
      d.overridden = false;  // the next scan takes its level
      any = true;
    }
  if (exact_ && exact_->simulates(int(x))) {
    exact_->mute_simulation(int(x), false);
    any = true;
  }
  return any;
}

void SimulatedCell::follow(const SimulatedCell& other) {
  if (other.overrides_ == followed_) return;
  followed_ = other.overrides_;
  const std::bitset<256> changed = overridden_ ^ other.overridden_;
  for (uint32_t x = 0; x < 256; ++x)
    if (changed[x]) {
      if (other.overridden_[x]) override_input(x);
      else resume(x);
    }
}

bool SimulatedCell::simulates(uint32_t x) const {
  if (exact_ && exact_->simulates(int(x))) return true;
  return std::any_of(drivers_.begin(), drivers_.end(), [x](const Driver& d) { return d.x == x; });
}

std::vector<uint32_t> SimulatedCell::simulated_inputs() const {
  std::vector<uint32_t> out;
  for (int x = 0; x < 16; ++x)
    if (exact_ && exact_->simulates(x)) out.push_back(uint32_t(x));
  for (const auto& d : drivers_) out.push_back(d.x);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void SimulatedCell::before_inputs(uint64_t now_us) {
  for (auto& d : drivers_) {
    bool v = d.signal->level(now_us, mem_);
    if (!v && scanned_ && std::find(captured_.begin(), captured_.end(), d.x) != captured_.end())
      v = d.signal->on_between(last_us_, now_us);
    if (!d.overridden) engine_.set_input(d.x, v);
  }
  scanned_ = true;
  last_us_ = now_us;
}

}  // namespace plc_cell
