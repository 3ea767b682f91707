#include "plc_cell/temp/thermal_plant.h"

#include <algorithm>
#include <cmath>

namespace plc_cell {
namespace temp {

ThermalPlant::ThermalPlant(const ThermalPlantParams& p) : p_(p), t_c_(p.initial_c) {
  const size_t bins = static_cast<size_t>(std::llround(p.dead_time_s * 1e6 / kBinUs));
  line_.assign(bins, 0.0);
}

void ThermalPlant::step(uint64_t dt_us, double heat, double cool) {
  heat = std::clamp(heat, 0.0, 1.0);
  cool = std::clamp(cool, 0.0, 1.0);
  const double drive = p_.gain_c * heat - p_.cooling_gain_c * cool;
  // Integrate bin by bin so the delay line and the exponential step see the same time.
  while (dt_us > 0) {
    const uint64_t chunk = std::min<uint64_t>(dt_us, kBinUs - bin_us_);
    bin_sum_ += drive * double(chunk);
    bin_us_ += chunk;
    const double u = line_.empty() ? drive : out_;
    const double target = p_.ambient_c + u;
    t_c_ = target + (t_c_ - target) * std::exp(-double(chunk) * 1e-6 / p_.tau_s);
    if (bin_us_ == kBinUs) {
      const double avg = bin_sum_ / double(kBinUs);
      bin_sum_ = 0;
      bin_us_ = 0;
      if (!line_.empty()) {
        out_ = line_[head_];  // the bin pushed dead_time ago
        line_[head_] = avg;
        head_ = (head_ + 1) % line_.size();
      }
    }
    dt_us -= chunk;
  }
}

}  // namespace temp
}  // namespace plc_cell
