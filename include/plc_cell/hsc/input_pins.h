#pragma once
// The high-speed inputs X0-X15 at the terminal, one InputPin each: what drives it (an
// analytic edge source, or explicit edges), its digital input filter (§9.7) and its
// capture latch (§9.6). The counters, the edge interrupts and the pulse measurements
// read the levels here.
#include <array>
#include <cstdint>
#include <vector>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/edge_source.h"
#include "plc_cell/hsc/hsc_config.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

struct InputPin {
  uint64_t filter_ns = 0;       // the filter's minimum pulse width, 0: none
  bool capture = false;         // a capture input
  EdgeSource* src = nullptr;    // its analytic driver, if any
  int phase = -1;               // which phase of src
  uint64_t gen = 0;             // filter: a raw change voids the pending output
  bool latch = false;           // capture: ON at some instant since the last image
  int64_t cap_q = 0;            // capture of an analytic pin: quarter at the last image

  // A source's pulses last half a period (50 % duty); shorter than the filter width
  // they are all lost, and the filtered input stays OFF.
  bool blocked() const;
  // The analytic level at t (OFF when blocked).
  bool source_level(uint64_t t_ns) const { return !blocked() && src->level(phase, src->quarter(t_ns)); }
  // The next edge of the analytic driver after now in the given direction, or kNever.
  uint64_t next_source_edge(bool rising, uint64_t now_ns) const;
  // Some quarter between the last image and now put the pin ON.
  bool source_was_on(uint64_t now_ns) const;
};

class InputPins {
 public:
  explicit InputPins(const HscConfig& cfg);

  InputPin& operator[](int x) { return pins_[x]; }
  const InputPin& operator[](int x) const { return pins_[x]; }
  bool driven(int x) const { return pins_[x].src != nullptr; }
  // Explicit level of x before the filter (what the terminal shows).
  bool raw(int x) const { return raw_[x] != 0; }
  void set_raw(int x, bool v) { raw_[x] = v ? 1 : 0; }
  // The pins with no analytic driver whose level in `inputs` (the engine's input
  // terminals X0-X15, one 0/1 byte each) differs from the raw one, as bits.
  uint16_t undriven_changes(const uint8_t* inputs) const;
  uint16_t driven_mask() const { return driven_; }
  // Explicit levels after the filter (an analytic pin keeps its last explicit one).
  const InputLevels& levels() const { return term_; }
  InputLevels& levels() { return term_; }
  // Terminal level of x at t: the source's if driven, else the explicit one.
  bool level(int x, uint64_t t_ns) const { return pins_[x].src ? pins_[x].source_level(t_ns) : term_[x]; }

  // Binds s to pin_a (phase 0) and pin_b (phase 1, -1: none); throws Error if a pin is not
  // X0-X15 or is driven already (pins bound before the throw stay bound: see unbind).
  void bind(EdgeSource* s, int pin_a, int pin_b);
  void unbind(const EdgeSource* s);

  void start(uint64_t t_ns, const ScanEngine& engine);
  // After the input image: filtered levels and capture latches of the pins that have
  // a filter or a capture.
  void image(uint64_t now_ns, Memory& mem);

 private:
  std::array<InputPin, 16> pins_;
  InputLevels term_{};
  // Kept packed apart from the pins, one byte per pin as the engine keeps its inputs: a
  // scan compares all sixteen at once (most scans find none changed).
  std::array<uint8_t, 16> raw_{};
  uint16_t driven_ = 0;  // bit x: pins_[x].src is set
  std::array<uint8_t, 16> undriven_bytes_;  // byte x: 0xFF while pins_[x].src is not set

  void set_driven(int x, bool on);
  std::vector<int> imaged_;  // inputs with a filter or a capture
};

}  // namespace hsc
}  // namespace plc_cell
