#include "plc_cell/scenario/resolution.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

std::string wall_time(uint64_t us) {
  char b[48];
  if (us < 1000000)
    std::snprintf(b, sizeof b, "%.1f ms", double(us) / 1000.0);
  else
    std::snprintf(b, sizeof b, "%.3f s", double(us) / 1e6);
  std::string s = b;
  if (s.size() > 5 && s.compare(s.size() - 5, 5, ".0 ms") == 0) s.erase(s.size() - 5, 2);  // "2 ms"
  return s;
}

std::string Resolution::text() const {
  return wall_time(us()) + ": a poll every " + wall_time(period_us) + " (the slowest of " + std::to_string(polls) +
         " round trips: " + wall_time(round_trip_us) + ") + that round trip + the cell's scan of " + wall_time(scan_us) +
         (age_us ? " + the age of the messages read, up to " + wall_time(age_us) : "");
}

Resolution measure_resolution(LinkedPlc& plc, const std::vector<Address>& addrs, uint64_t scan_us, int polls) {
  Resolution r;
  r.scan_us = scan_us;
  if (!addrs.empty()) plc.read(addrs);  // connects
  for (int i = 0; i < polls && !addrs.empty(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    plc.read(addrs);
    const auto us = std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0);
    r.round_trip_us = std::max<uint64_t>(r.round_trip_us, uint64_t(us.count()));
    ++r.polls;
  }
  // Whole tenths of a millisecond, rounded up: the figure is printed and compared.
  r.round_trip_us = (r.round_trip_us + 99) / 100 * 100;
  r.period_us = std::max((r.round_trip_us + 999) / 1000 * 1000, kMinPollPeriodUs);
  r.age_us = plc.max_age_us();
  return r;
}

}  // namespace scenario
}  // namespace plc_cell
