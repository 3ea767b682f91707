#pragma once
// The cell's time as its front end runs it, not read from the cell file: virtual time
// (plc_cell sim, test, explore, check, plc_node ~virtual_time) or real time (plc_cell run,
// plc_node), and where its calendar starts (what keeps the date and time: the RTC,
// docs/analog-and-temperature.md "Real-time clock").
#include <string>

namespace plc_cell {

struct CellClock {
  // Nothing of a cell in virtual time reads the host's clock: the same run gives the same
  // memory, scan for scan, whenever it is made.
  bool virtual_time = true;
  // --rtc-start, ~rtc_start: "" (the cell's own modules.rtc.start, else the clock's
  // default), "host" (the host's local time), or a date-time 2026-01-01T00:00:00.
  std::string calendar_start;
};

}  // namespace plc_cell
