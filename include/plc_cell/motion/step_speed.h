#pragma once
// The stepper ramp of an axis given in steps (the cell YAML's `stepspeed:`, the TRi
// FMD1616's STEPSPEED ch, pps, acc): a maximum speed and the steps from standstill to
// it. It replaces FUN141's time-based ramp (P4, P5, P8, P12) for that axis's FUN140
// moves (docs/motion.md "Step-count ramps (stepspeed:)").
#include <cstdint>
#include <string>

#include <yaml-cpp/yaml.h>

namespace plc_cell {

class YamlReader;

namespace motion {

constexpr int64_t kStepMaxPps = 10000;         // the FMD1616's rated pulse rate
constexpr int64_t kStepMaxAccel = 2147483647;  // 2^31 - 1: the manual's maximum step count

struct StepSpeed {
  bool used = false;
  int64_t pps = 0;          // maximum speed V, pulses/s (1-10000)
  int64_t accel_steps = 0;  // S: steps from standstill to V and from V to a stop
  int done = -1;            // completion relay M0-M1911, -1: none
  int line = 0;             // where it was configured

  double max_hz() const { return static_cast<double>(pps); }
  // The pulse train starts and ends at V/8 (the manual's velocity profile) ...
  double start_hz() const { return static_cast<double>(pps) / 8.0; }
  // ... and changes speed at the manual's A = V^2 / 2S exactly, so a full ramp
  // V/8 -> V covers 63/64 S steps: the 1/64 S from standstill to V/8 is the jump.
  double accel() const { return static_cast<double>(pps) * static_cast<double>(pps) / (2.0 * accel_steps); }
};

// `stepspeed: {pps: 100, accel_steps: 50, done: M100}` at v; throws SourceError
// naming the line of the bad key or value.
StepSpeed parse_step_speed(const YamlReader& r, const YAML::Node& v, const std::string& key);

}  // namespace motion
}  // namespace plc_cell
