#include "plc_cell/temp/rtc.h"

#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/area.h"
#include "plc_cell/temp/rtc_calibration.h"

namespace plc_cell {
namespace temp {
namespace {

constexpr int64_t kUsPerS = 1000000;
constexpr int64_t kEnd = int64_t(36525) * 86400 * kUsPerS;  // 2100-01-01: 100 years, 25 of them leap

DateTime host_local_time(int64_t given) {
  const std::time_t t =
      given ? std::time_t(given) : std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  localtime_r(&t, &tm);
  DateTime d;
  d.year = tm.tm_year + 1900, d.month = tm.tm_mon + 1, d.day = tm.tm_mday;
  d.hour = tm.tm_hour, d.minute = tm.tm_min, d.second = tm.tm_sec;
  if (!valid(d)) d = DateTime{};  // a host clock outside the RTC's century
  return d;
}

}  // namespace

RtcConfig parse_rtc_config(const YAML::Node& node, const std::string& file) {
  RtcConfig c;
  if (!node || node.IsNull()) return c;  // no modules.rtc: the host's time
  YamlReader r(file);
  r.only(node, "modules.rtc", {"start", "drift"});
  if (const YAML::Node s = node["start"]) {
    const auto t = parse_date_time(r.str(s, "modules.rtc.start"));
    if (!t) r.fail(s, "modules.rtc.start", "expected a date-time 2000-01-01T00:00:00 .. 2099-12-31T23:59:59");
    c.has_start = true;
    c.start = *t;
  }
  if (node["drift"]) c.drift_s_per_day = r.number(node["drift"], "modules.rtc.drift", -100, 100);
  return c;
}

Rtc::Rtc(RtcConfig cfg, Memory& mem) : cfg_(cfg), mem_(mem) {
  us_ = to_seconds(cfg_.has_start ? cfg_.start : host_local_time(0)) * kUsPerS;
}

int Rtc::week() const { return (weekday(seconds()) + week_offset_) % 7; }

void Rtc::before_inputs(uint64_t now_us) {
  if (!started_) {
    started_ = true;
    last_us_ = now_us;
    // The host's time when the cell starts scanning, not when it was built.
    if (!cfg_.has_start) us_ = to_seconds(host_local_time(host_time_)) * kUsPerS;
    return;
  }
  if (now_us <= last_us_) return;
  const uint64_t dt = now_us - last_us_;
  last_us_ = now_us;
  // The crystal's error minus what D4054 corrects (the S35390A's digital calibration).
  const uint16_t code = mem_.reg(Area::D, rtcreg::kCalibration);
  if (code != calibration_code_) {
    calibration_code_ = code;
    calibration_ = rtc_calibration_rate(code).value_or(0.0);
  }
  const double rate = cfg_.drift_s_per_day - calibration_;
  if (rate == 0.0) {  // an exact crystal (the usual cell): the residual stays below 1 us
    us_ += static_cast<int64_t>(dt);
    if (us_ >= kEnd) us_ -= kEnd;
    return;
  }
  residual_us_ += static_cast<double>(dt) * rate / 86400.0;
  const double whole = std::trunc(residual_us_);
  residual_us_ -= whole;
  us_ += static_cast<int64_t>(dt) + static_cast<int64_t>(whole);
  if (us_ >= kEnd) us_ -= kEnd;  // the two-digit year wraps to 2000 (plc_cell's choice)
  if (us_ < 0) us_ = 0;
}

void Rtc::on_stop() {
  // STOP -> RUN clears M1952/M1953: no edge may come from before the STOP.
  prev_stop_read_ = false;
  prev_round_ = false;
}

void Rtc::set_from_registers() {
  DateTime t;
  t.second = mem_.reg(Area::R, rtcreg::kSecond);
  t.minute = mem_.reg(Area::R, rtcreg::kMinute);
  t.hour = mem_.reg(Area::R, rtcreg::kHour);
  t.day = mem_.reg(Area::R, rtcreg::kDay);
  t.month = mem_.reg(Area::R, rtcreg::kMonth);
  const uint16_t year = mem_.reg(Area::R, rtcreg::kYear);
  const uint16_t week = mem_.reg(Area::R, rtcreg::kWeek);
  t.year = 2000 + year;
  if (year > 99 || week > 6 || !valid(t)) {
    mem_.set_bit(Area::M, rtcreg::kSetError, true);  // and the clock keeps its time
    return;
  }
  mem_.set_bit(Area::M, rtcreg::kSetError, false);
  us_ = to_seconds(t) * kUsPerS;
  residual_us_ = 0;
  // The chip keeps the week it is given and counts it on at midnight.
  week_offset_ = (week - weekday(seconds()) + 7) % 7;
  published_s_ = -1;
}

void Rtc::round_to_minute() {
  const int64_t s = seconds();
  const int64_t minute = s - s % 60;
  us_ = (s % 60 < 30 ? minute : minute + 60) * kUsPerS;
  residual_us_ = 0;
}

void Rtc::before_program(uint64_t) {
  mem_.set_reg(Area::D, rtcreg::kChipType, rtcreg::kChipS35390A);
  mem_.set_bit(Area::M, rtcreg::kInstalled, true);
  const bool stop_read = mem_.bit(Area::M, rtcreg::kStopRead);
  const bool round = mem_.bit(Area::M, rtcreg::kRound30s);
  if (prev_stop_read_ && !stop_read) set_from_registers();
  if (round && !prev_round_) round_to_minute();
  prev_stop_read_ = stop_read;
  prev_round_ = round;
  if (stop_read) return;  // the program owns R4128-R4135 while it sets the clock
  publish();
}

void Rtc::attached(ScanEngine&) {
  // A host link or Modbus master may read the clock before the first scan: a real
  // controller never reports month 0 or the year 2000 of cleared registers.
  if (!mem_.bit(Area::M, rtcreg::kStopRead)) publish();
}

void Rtc::on_run() {
  publish();  // STOP -> RUN cleared R4128-R4135 (and M1952)
}

void Rtc::publish() {
  if (seconds() != published_s_) find_registers();
  // Every scan, whatever a client or the program wrote there since.
  static_assert(rtcreg::kHourMinute == rtcreg::kSecond + 7, "R4128-R4135 are one block");
  std::memcpy(mem_.words(Area::R) + rtcreg::kSecond, registers_, sizeof registers_);
}

void Rtc::find_registers() {
  published_s_ = seconds();
  const DateTime t = from_seconds(published_s_);
  registers_[0] = static_cast<uint16_t>(t.second);
  registers_[1] = static_cast<uint16_t>(t.minute);
  registers_[2] = static_cast<uint16_t>(t.hour);
  registers_[3] = static_cast<uint16_t>(t.day);
  registers_[4] = static_cast<uint16_t>(t.month);
  registers_[5] = static_cast<uint16_t>(t.year - 2000);
  registers_[6] = static_cast<uint16_t>((weekday(published_s_) + week_offset_) % 7);
  registers_[7] = static_cast<uint16_t>(t.hour << 8 | t.minute);
}

namespace {

// The start the cell's clock gives (its calendar_start, else kVirtualCalendarStart in
// virtual time) over what modules.rtc said.
void apply_cell_clock(const CellClock& clock, RtcConfig* c) {
  if (clock.calendar_start == "host") {
    c->has_start = false;
  } else if (!clock.calendar_start.empty()) {
    const std::string why = calendar_start_problem(clock.calendar_start);
    if (!why.empty()) throw Error("RTC start " + clock.calendar_start + ": " + why);
    c->has_start = true;
    c->start = *parse_date_time(clock.calendar_start);
  } else if (!c->has_start && clock.virtual_time) {
    c->has_start = true;
    c->start = *parse_date_time(kVirtualCalendarStart);
  }
}

}  // namespace

std::string calendar_start_problem(const std::string& text) {
  if (text == "host" || parse_date_time(text)) return "";
  return "expected host or a date-time 2000-01-01T00:00:00 .. 2099-12-31T23:59:59";
}

std::unique_ptr<Rtc> make_rtc(const YAML::Node& document, const std::string& file, Memory& mem,
                              const CellClock& clock) {
  const YAML::Node modules = document.IsMap() ? document["modules"] : YAML::Node();
  const YAML::Node node = modules && modules.IsMap() ? modules["rtc"] : YAML::Node();
  RtcConfig c = parse_rtc_config(node, file);
  apply_cell_clock(clock, &c);
  return std::make_unique<Rtc>(c, mem);
}

}  // namespace temp
}  // namespace plc_cell
