#pragma once
// `counters.pulse_measurement`: which counting inputs are also measured (pulse width,
// period, frequency: TRi FMD1616 Ch. 8), in which unit and with which timeout.
// docs/counters-and-interrupts.md "Pulse measurement" describes the keys.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace plc_cell {
namespace hsc {

struct CounterDef;

struct PulseMeasurementConfig {
  std::vector<int> inputs;      // X0-X15, each a counting input of a configured counter
  std::vector<int> counter_of;  // the counter (HSCn) each input counts for
  bool tenths = false;          // width and period in 0.1 us (TRi SETSYSTEM 20,1), else us
  uint64_t timeout_ns = 0;      // 0: twice the last period

  bool measured(int x) const;
  const char* unit() const { return tenths ? "0.1us" : "us"; }
  double in_unit(uint64_t ns) const { return double(ns) / (tenths ? 100.0 : 1000.0); }
};

// node: the `pulse_measurement` mapping (null: nothing measured); counters: the parsed
// hscN entries. Throws SourceError at file:line:column.
PulseMeasurementConfig parse_pulse_measurement(const YAML::Node& node, const std::string& file,
                                               const std::array<CounterDef, 8>& counters);

}  // namespace hsc
}  // namespace plc_cell
