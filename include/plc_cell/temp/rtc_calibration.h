#pragma once
// The FBs RTC calibration register D4054 (S35390A chip, D4053 = 3): the manual's
// table of codes and the rate each corrects (manual chapter 15.3, A:5316-A:5370).
#include <cstdint>
#include <optional>

namespace plc_cell {
namespace temp {

// The error (s/day, + = the clock runs fast) a D4054 code compensates: 0000H -> 0,
// a code of the table -> its rate, anything else -> nullopt (no correction).
std::optional<double> rtc_calibration_rate(uint16_t code);

// The table's code for a rate (s/day), nullopt if the table has no such entry
// (the rates are matched to 0.005 s/day).
std::optional<uint16_t> rtc_calibration_code(double rate_s_per_day);

}  // namespace temp
}  // namespace plc_cell
