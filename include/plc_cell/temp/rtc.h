#pragma once
// The FBs real-time clock (manual chapter 15) as a ScanHook: R4128-R4135 hold the
// clock from the moment the hook is attached and follow it on every RUN scan; M1952
// stops the copy and its falling edge sets the clock from R4128-R4134; M1953 rounds to the minute; D4054 calibrates the rate.
// The clock runs on the engine's clock: virtual time in tests and `plc_cell sim`,
// the host's steady clock in real time. It starts at modules.rtc.start; without one, at
// kVirtualCalendarStart in virtual time and at the host's local time in real time (the
// cell's clock, config/cell_clock.h, says which, and may override the start).
// docs/analog-and-temperature.md, RTC.
#include <cstdint>
#include <memory>
#include <string>

#include <yaml-cpp/yaml.h>

#include "plc_cell/config/cell_clock.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/temp/rtc_calendar.h"

namespace plc_cell {
namespace temp {

namespace rtcreg {
constexpr uint32_t kSecond = 4128, kMinute = 4129, kHour = 4130, kDay = 4131, kMonth = 4132, kYear = 4133,
                   kWeek = 4134, kHourMinute = 4135;
constexpr uint32_t kStopRead = 1952, kRound30s = 1953, kInstalled = 1954, kSetError = 1955;  // M
constexpr uint32_t kChipType = 4053, kCalibration = 4054;                                    // D
constexpr uint16_t kChipS35390A = 3;  // the chip with digital calibration
}  // namespace rtcreg

// Where the clock of a cell in virtual time starts when neither modules.rtc.start nor
// --rtc-start (~rtc_start) says: a Monday, at midnight.
constexpr const char* kVirtualCalendarStart = "2024-01-01T00:00:00";

// modules.rtc in the cell YAML.
struct RtcConfig {
  bool has_start = false;  // false: the host's local time when the cell starts
  DateTime start;
  double drift_s_per_day = 0;  // the emulated crystal's error (+ = runs fast)
};
RtcConfig parse_rtc_config(const YAML::Node& node, const std::string& file);

class Rtc final : public ScanHook {
 public:
  Rtc(RtcConfig cfg, Memory& mem);
  void before_inputs(uint64_t now_us) override;   // the clock runs, in RUN and STOP
  void before_program(uint64_t now_us) override;  // M1952/M1953 and the RTCR
  void on_stop() override;
  void attached(ScanEngine& engine) override;     // the registers hold the clock at once
  void on_run() override;                          // and again once STOP -> RUN cleared them

  // A clock that starts from the host's local time takes it from here (Unix seconds) rather
  // than reading it at the first scan: the two halves of a lockstep cell read it once.
  void set_host_time(int64_t unix_s) { host_time_ = unix_s; }

  int64_t seconds() const { return us_ / 1000000; }  // since 2000-01-01 00:00:00
  DateTime now() const { return from_seconds(seconds()); }
  int week() const;  // R4134: 0 = Sunday, or what the program set

 private:
  void set_from_registers();
  void round_to_minute();
  void publish();  // the clock into R4128-R4135
  void find_registers();  // registers_ for the present second

  RtcConfig cfg_;
  Memory& mem_;
  int64_t host_time_ = 0;  // 0: read the host's clock
  bool started_ = false;
  uint64_t last_us_ = 0;
  int64_t us_ = 0;          // the clock, microseconds since 2000-01-01 00:00:00
  double residual_us_ = 0;  // drift and calibration not yet whole microseconds
  int week_offset_ = 0;     // the program's week minus the calendar's
  bool prev_stop_read_ = false;
  bool prev_round_ = false;
  // R4128-R4135 as publish() writes them. The calendar walks years and months: it is
  // found again only when the second or the week's offset changes (published_s_ = -1),
  // and a scan within the second copies 16 bytes.
  int64_t published_s_ = -1;
  uint16_t registers_[8] = {};
  // D4054 rarely changes: its rate is looked up in the table only when it does.
  int calibration_code_ = -1;
  double calibration_ = 0;  // what that code corrects, s/day
};

// Why text is no calendar start (CellClock::calendar_start: "host" or a date-time), or "".
std::string calendar_start_problem(const std::string& text);

// The cell's RTC (every FBs MC/MN main unit has one), configured by modules.rtc and the
// cell's clock (whose calendar_start wins over modules.rtc.start). Throws Error for a
// calendar_start that is neither "host" nor a date-time.
std::unique_ptr<Rtc> make_rtc(const YAML::Node& document, const std::string& file, Memory& mem,
                              const CellClock& clock = {});

}  // namespace temp
}  // namespace plc_cell
