#include "plc_cell/hsc/input_pins.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace hsc {

bool InputPin::blocked() const {
  return src && filter_ns > 0 && 2.0 * std::abs(src->rate_hz()) * double(filter_ns) > 1e9;
}

uint64_t InputPin::next_source_edge(bool rising, uint64_t now_ns) const {
  const int dir = src->direction();
  if (dir == 0 || blocked()) return Component::kNever;
  const int64_t q = src->quarter(now_ns);
  for (int i = 1; i <= 4; ++i) {
    const bool a = src->level(phase, q + (i - 1) * dir), b = src->level(phase, q + i * dir);
    if (a != b && b == rising) return src->time_of_quarter(q + i * dir, now_ns);
  }
  return Component::kNever;
}

// A pulse phase is ON in 2 of any 4 consecutive quarters, so 3 quarters always contain one.
bool InputPin::source_was_on(uint64_t now_ns) const {
  if (blocked()) return false;
  const int64_t q1 = src->quarter(now_ns);
  const int64_t lo = std::min(cap_q, q1), hi = std::max(cap_q, q1);
  if (hi - lo >= 3) return true;
  for (int64_t q = lo; q <= hi; ++q)
    if (src->level(phase, q)) return true;
  return false;
}

InputPins::InputPins(const HscConfig& cfg) {
  undriven_bytes_.fill(0xFF);
  for (int x = 0; x < 16; ++x) {
    pins_[x].filter_ns = cfg.filter_ns[x];
    pins_[x].capture = cfg.capture[x];
    if (pins_[x].filter_ns > 0 || pins_[x].capture) imaged_.push_back(x);
  }
}

void InputPins::bind(EdgeSource* s, int pin_a, int pin_b) {
  for (int k = 0; k < 2; ++k) {
    const int x = k == 0 ? pin_a : pin_b;
    if (x < 0) continue;
    if (x > 15) throw Error(s->name() + ": X" + std::to_string(x) + " is not a high-speed input (X0-X15)");
    if (pins_[x].src) throw Error("counters.sources: X" + std::to_string(x) + " is driven by both " +
                                  pins_[x].src->name() + " and " + s->name());
    pins_[x].src = s;
    pins_[x].phase = k;
    set_driven(x, true);
  }
}

void InputPins::unbind(const EdgeSource* s) {
  for (int x = 0; x < 16; ++x)
    if (pins_[x].src == s) {
      pins_[x].src = nullptr;
      pins_[x].phase = -1;
      set_driven(x, false);
    }
}

void InputPins::set_driven(int x, bool on) {
  driven_ = static_cast<uint16_t>(on ? driven_ | (1u << x) : driven_ & ~(1u << x));
  undriven_bytes_[x] = on ? 0 : 0xFF;
}

uint16_t InputPins::undriven_changes(const uint8_t* inputs) const {
  uint64_t in[2], raw[2], undriven[2];
  std::memcpy(in, inputs, sizeof in);
  std::memcpy(raw, raw_.data(), sizeof raw);
  std::memcpy(undriven, undriven_bytes_.data(), sizeof undriven);
  if ((((in[0] ^ raw[0]) & undriven[0]) | ((in[1] ^ raw[1]) & undriven[1])) == 0) return 0;
  uint16_t changed = 0;
  for (int x = 0; x < 16; ++x)
    if (inputs[x] != raw_[x]) changed = static_cast<uint16_t>(changed | (1u << x));
  return static_cast<uint16_t>(changed & ~driven_);
}

void InputPins::start(uint64_t t_ns, const ScanEngine& engine) {
  for (int x = 0; x < 16; ++x) {
    InputPin& p = pins_[x];
    if (!p.src) {
      term_[x] = engine.input(x);
      set_raw(x, engine.input(x));
    } else {
      p.cap_q = p.src->quarter(t_ns);
    }
    ++p.gen;  // filter outputs pending from the last run are void
    p.latch = false;
  }
}

void InputPins::image(uint64_t now_ns, Memory& mem) {
  for (int x : imaged_) {
    InputPin& p = pins_[x];
    bool on = false;
    if (p.src) {
      if (p.capture) on = p.source_was_on(now_ns);
      p.cap_q = p.src->quarter(now_ns);
    } else {
      if (p.filter_ns > 0) mem.set_bit(Area::X, x, term_[x]);  // the terminal shows the raw level
      on = p.latch && p.capture;
      p.latch = term_[x];  // ON now: ON just after this image, too
    }
    if (on) mem.set_bit(Area::X, x, true);
  }
}

}  // namespace hsc
}  // namespace plc_cell
