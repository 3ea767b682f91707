#pragma once
// The `counters:` section of the cell YAML: HSC0-HSC7, external edge interrupts,
// capture inputs, the digital input filter and the simulated pulse sources that
// drive counter inputs.
// docs/counters-and-interrupts.md describes every key.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/address.h"
#include "plc_cell/hsc/count_rule.h"
#include "plc_cell/hsc/decoding.h"
#include "plc_cell/hsc/input_filter.h"
#include "plc_cell/hsc/pulse_measurement.h"

namespace plc_cell {
namespace hsc {

constexpr int kNoPin = -1;

struct CounterDef {
  bool used = false;
  bool timer = false;        // HSC0-3 configured as HST0-3
  Mode mode = Mode::UD;
  Decoding decoding = Decoding::Fatek;  // TRi decoding of an A/B counter (MD4 only); Fatek: by mode
  int pin_a = kNoPin;        // U, P or A
  int pin_b = kNoPin;        // D, R or B (MD2/MD3 without it: the direction relay)
  int pin_mask = kNoPin;
  int pin_clear = kNoPin;
  bool inv_count = false, inv_mask = false, inv_clear = false;  // HHSC polarity
  std::string name;          // ROS topic name; "hsc<n>" if not given
  int line = 0;              // where it was configured (1-based)
};

struct SourceDef {
  std::string name;
  int pin_a = kNoPin, pin_b = kNoPin;  // b: encoder only
  double hz = 0;                        // periods per second (per phase); < 0 backwards
  bool has_follow = false;              // runs only while this output is on
  Address follow{};
};

struct ScheduledEdge {
  uint64_t t_ns;
  int x;
  bool level;
};

struct HscConfig {
  std::array<CounterDef, 8> counters;
  std::vector<int> edge_interrupts;  // 2*x + (falling ? 1 : 0)
  std::vector<SourceDef> sources;
  std::vector<ScheduledEdge> edges;  // exact-time switch signals on X0-X15
  // Digital input filter (§9.7): minimum ON/OFF pulse width per input X0-X35, 0 = none.
  std::array<uint64_t, kFilteredInputs> filter_ns{};
  // Capture inputs (§9.6): an ON pulse between two scans is seen for one scan.
  std::array<bool, kFilteredInputs> capture{};
  uint64_t frequency_window_us = 100000;
  double publish_rate_hz = 10;
  PulseMeasurementConfig pulse;  // counters.pulse_measurement
};

// Resource table of the manual (§10.2): fixed HHSC pins and the relays.
struct HhscPins {
  std::vector<int> a;  // allowed U/P/A pins, the first is the default (A of the A/B pair)
  int b, mask, clear;
};
const HhscPins& hhsc_pins(int n);
uint32_t mask_relay(int n);              // M1940 ...
int clear_relay(int n);                  // M1941 ... or -1 for SHSC
uint32_t dir_relay(int n);               // M1942 ...
inline uint32_t cv_register(int n) { return 4096 + 4 * n; }  // DR4096 ... (R area)
inline uint32_t pv_register(int n) { return 4098 + 4 * n; }
constexpr uint32_t kHstaCv = 4152;       // DR4152
constexpr uint32_t kHstaPv = 4154;       // R4154: plc_cell's choice (the manual names none)
constexpr uint32_t kTimeBaseMask = 4162; // R4162

// Parses node (the `counters:` mapping; null = nothing configured). Throws
// SourceError with file:line:column, e.g. for an input used twice.
HscConfig parse_hsc_config(const YAML::Node& node, const std::string& file);

}  // namespace hsc
}  // namespace plc_cell
