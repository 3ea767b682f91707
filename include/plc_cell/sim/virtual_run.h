#pragma once
// Runs a Plc in virtual time: a fixed number of scans of a fixed period, with
// every change of the watched addresses reported at its virtual time.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {

struct WatchChange {
  uint64_t t_us;
  size_t watch;  // index into the watch list
  uint32_t value;
};

class VirtualRun {
 public:
  VirtualRun(Plc& plc, uint64_t scan_period_us) : plc_(plc), period_us_(scan_period_us) {}

  size_t watch(const Address& a);
  // Scans at t = now, now + period, ... while t < now + duration (so 2.5 s at 1 ms is 2500 scans).
  void run_for(uint64_t duration_us, const std::function<void(const WatchChange&)>& on_change = {});
  std::vector<uint32_t> values() const;
  uint64_t now_us() const { return now_us_; }
  uint64_t scans() const { return scans_; }

 private:
  Plc& plc_;
  uint64_t period_us_;
  uint64_t now_us_ = 0;
  uint64_t scans_ = 0;
  std::vector<Address> watches_;
  std::vector<uint32_t> last_;
  std::vector<bool> seen_;
};

}  // namespace plc_cell
