#pragma once
// How finely a wall-clock target sees time (docs/testing-on-hardware.md, "Resolution"): it
// polls every `period` (its slowest measured round trip, at least kMinPollPeriodUs), a poll's
// values are the PLC's at some moment of its round trip, and the PLC acts on what was
// written at its next scan. So a change is seen within period + round trip + one scan of
// when it happened (plus, for a link that reads what a node published, the age of its
// messages): the resolution a time window must not be tighter than.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/scenario/linked_plc.h"

namespace plc_cell {
namespace scenario {

// A host link is not polled faster than this, however fast it answers.
constexpr uint64_t kMinPollPeriodUs = 2000;

struct Resolution {
  uint64_t round_trip_us = 0;  // the slowest poll measured
  uint64_t period_us = 0;      // one poll every
  uint64_t scan_us = 0;        // the cell's scan period (plc.scan_period)
  uint64_t age_us = 0;         // how old a value read may be (LinkedPlc::max_age_us)
  uint64_t polls = 0;          // how many were measured
  uint64_t us() const { return period_us + round_trip_us + scan_us + age_us; }
  // "3.4 ms: a poll every 2 ms (the slowest of 20 round trips: 0.4 ms) + that round trip +
  // the cell's scan of 1 ms"
  std::string text() const;
};

// A duration measured on the wall clock as a report shows it: "3.4 ms", "1.102 s".
std::string wall_time(uint64_t us);

// Polls addrs (after one poll to connect) `polls` times back to back and takes the slowest
// (rounded up to 0.1 ms); the period is that in whole milliseconds. Throws CommError when
// the link fails.
Resolution measure_resolution(LinkedPlc& plc, const std::vector<Address>& addrs, uint64_t scan_us, int polls = 20);

}  // namespace scenario
}  // namespace plc_cell
