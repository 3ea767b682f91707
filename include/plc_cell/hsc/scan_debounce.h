#pragma once
// The digital input filter for inputs that the cell presents only at the scans
// (X16-X35, and ROS or per-scan simulated levels): a debounce on the scan's samples.
// A new level passes once it has been sampled unchanged for the filter time; a
// shorter ON or OFF pulse is lost, a longer one arrives the filter time late.
#include <cstdint>

namespace plc_cell {
namespace hsc {

class ScanDebounce {
 public:
  explicit ScanDebounce(uint64_t width_ns = 0) : width_(width_ns) {}
  // The filtered level for the raw sample taken at t_ns (samples in time order).
  bool sample(bool raw, uint64_t t_ns);
  void reset() { started_ = false; }

 private:
  uint64_t width_;
  bool started_ = false;
  bool stable_ = false;
  bool pending_ = false;
  uint64_t since_ = 0;  // when the raw level first differed from stable_
};

}  // namespace hsc
}  // namespace plc_cell
