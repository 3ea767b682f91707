#pragma once
// Civil date-time for the FBs RTC: years 2000-2099 (the RTC's two-digit year),
// seconds since 2000-01-01 00:00:00, day of week 0 = Sunday.
#include <cstdint>
#include <optional>
#include <string>

namespace plc_cell {
namespace temp {

struct DateTime {
  int year = 2000;  // 2000..2099
  int month = 1, day = 1, hour = 0, minute = 0, second = 0;
};

bool valid(const DateTime& t);
int days_in_month(int year, int month);
int64_t to_seconds(const DateTime& t);        // since 2000-01-01 00:00:00
DateTime from_seconds(int64_t s);             // s >= 0
int weekday(int64_t s);                       // 0 = Sunday .. 6 = Saturday
// "2026-01-01T00:00:00" (or a space for the T); nullopt if malformed or out of range.
std::optional<DateTime> parse_date_time(const std::string& text);

}  // namespace temp
}  // namespace plc_cell
