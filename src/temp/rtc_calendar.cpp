#include "plc_cell/temp/rtc_calendar.h"

#include <cstdio>

namespace plc_cell {
namespace temp {
namespace {

bool leap(int y) { return (y % 4 == 0 && y % 100 != 0) || y % 400 == 0; }

// Days from 1970-01-01 to y-m-d (H. Hinnant's days_from_civil).
int64_t days_from_civil(int64_t y, unsigned m, unsigned d) {
  y -= m <= 2;
  const int64_t era = (y >= 0 ? y : y - 399) / 400;
  const unsigned yoe = static_cast<unsigned>(y - era * 400);
  const unsigned doy = (153 * (m + (m > 2 ? -3 : 9)) + 2) / 5 + d - 1;
  const unsigned doe = yoe * 365 + yoe / 4 - yoe / 100 + doy;
  return era * 146097 + static_cast<int64_t>(doe) - 719468;
}

const int64_t kEpochDays = days_from_civil(2000, 1, 1);

}  // namespace

int days_in_month(int year, int month) {
  static const int d[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12) return 0;
  return month == 2 && leap(year) ? 29 : d[month - 1];
}

bool valid(const DateTime& t) {
  return t.year >= 2000 && t.year <= 2099 && t.month >= 1 && t.month <= 12 && t.day >= 1 &&
         t.day <= days_in_month(t.year, t.month) && t.hour >= 0 && t.hour <= 23 && t.minute >= 0 &&
         t.minute <= 59 && t.second >= 0 && t.second <= 59;
}

int64_t to_seconds(const DateTime& t) {
  const int64_t days = days_from_civil(t.year, static_cast<unsigned>(t.month), static_cast<unsigned>(t.day)) - kEpochDays;
  return days * 86400 + t.hour * 3600 + t.minute * 60 + t.second;
}

DateTime from_seconds(int64_t s) {
  DateTime t;
  int64_t days = s / 86400;
  int64_t rem = s % 86400;
  t.hour = static_cast<int>(rem / 3600);
  t.minute = static_cast<int>(rem % 3600 / 60);
  t.second = static_cast<int>(rem % 60);
  // A hundred years at most: walk years and months.
  int y = 2000;
  while (days >= (leap(y) ? 366 : 365)) days -= leap(y) ? 366 : 365, ++y;
  int m = 1;
  while (days >= days_in_month(y, m)) days -= days_in_month(y, m), ++m;
  t.year = y;
  t.month = m;
  t.day = static_cast<int>(days) + 1;
  return t;
}

int weekday(int64_t s) {
  // 2000-01-01 was a Saturday (6).
  return static_cast<int>((s / 86400 + 6) % 7);
}

std::optional<DateTime> parse_date_time(const std::string& text) {
  DateTime t;
  char sep = 0;
  int n = 0;
  if (std::sscanf(text.c_str(), "%4d-%2d-%2d%c%2d:%2d:%2d%n", &t.year, &t.month, &t.day, &sep, &t.hour, &t.minute,
                  &t.second, &n) != 7 ||
      static_cast<size_t>(n) != text.size() || (sep != 'T' && sep != ' ') || !valid(t))
    return std::nullopt;
  return t;
}

}  // namespace temp
}  // namespace plc_cell
