#include "plc_cell/sim/lockstep_cells.h"

#include <ctime>

#include "plc_cell/core/native/lockstep.h"
#include "plc_cell/temp/rtc.h"

namespace plc_cell {

void run_in_lockstep(SoftCell& cell, SoftCell& twin) {
  SimulatedCell& played = cell.simulation();
  SimulatedCell& follower = twin.simulation();
  temp::Rtc* const clocks[] = {cell.get<temp::Rtc>(), twin.get<temp::Rtc>()};
  bool first = true;
  auto mirror = [&played, &follower, clocks, first]() mutable {
    follower.follow(played);
    if (!first) return;
    first = false;
    // A clock that starts from the host's local time reads it at its first scan: one
    // reading for both, or the two could fall on either side of a second.
    const int64_t now = int64_t(std::time(nullptr));
    for (temp::Rtc* rtc : clocks)
      if (rtc) rtc->set_host_time(now);
  };
  auto lockstep = std::make_unique<Lockstep>(twin.plc(), std::move(mirror));
  cell.plc().locked([&](ScanEngine& e, Memory&) {
    e.set_lockstep(std::move(lockstep));
    return 0;
  });
}

}  // namespace plc_cell
