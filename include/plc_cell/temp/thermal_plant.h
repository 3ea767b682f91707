#pragma once
// A thermal plant: first order plus dead time, with losses to ambient.
//   tau dT/dt = gain * u(t - dead_time) - (T - ambient),   u = heater power 0..1
// so full power holds ambient + gain at steady state. Pure math, stepped in virtual time.
#include <cstddef>
#include <cstdint>
#include <vector>

namespace plc_cell {
namespace temp {

struct ThermalPlantParams {
  double ambient_c = 25;
  double initial_c = 25;
  double gain_c = 300;        // rise above ambient at full power, degC
  double tau_s = 300;         // time constant, s
  double dead_time_s = 5;     // transport delay of the heater power, s
  double cooling_gain_c = 0;  // drop below ambient at full cooling (a second actuator), degC
};

class ThermalPlant {
 public:
  explicit ThermalPlant(const ThermalPlantParams& p);

  // Advances dt_us with heater power u (0..1) and cooling power (0..1) held over the step.
  void step(uint64_t dt_us, double heat, double cool = 0);
  double temperature_c() const { return t_c_; }
  const ThermalPlantParams& params() const { return p_; }

 private:
  // The delay line holds the power averaged over 10 ms bins: exact enough for dead
  // times of seconds, and bounded memory at any scan period.
  static constexpr uint64_t kBinUs = 10000;

  ThermalPlantParams p_;
  double t_c_;
  std::vector<double> line_;  // ring of bin averages (net drive in degC)
  size_t head_ = 0;
  double bin_sum_ = 0;
  uint64_t bin_us_ = 0;
  double out_ = 0;  // the delayed drive currently applied
};

}  // namespace temp
}  // namespace plc_cell
