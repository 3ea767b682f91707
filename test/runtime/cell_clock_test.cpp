// The cell's clock (config/cell_clock.h): every virtual-time cell starts its calendar at the
// documented instant unless the cell (modules.rtc.start) or an option (rtc_start) says
// otherwise; a cell served in real time starts from the host's local time
// (docs/analog-and-temperature.md, "Real-time clock").
#include <gtest/gtest.h>

#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "../reliability/temp_dir.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/temp/rtc_calendar.h"

using namespace plc_cell;

namespace {

std::string write_cell(const TempDir& d, const std::string& yaml = "") {
  std::ofstream(d.path() + "/c.il") << "ORG M1925\nMOV S=R4128 D=R0\nEND\n";
  std::ofstream(d.path() + "/c.yaml") << "cell: {name: c, program: c.il}\n" << yaml;
  return d.path() + "/c.yaml";
}

// R4128-R4135 after the first scan.
std::vector<uint32_t> clock_at_scan_1(Cell& cell) {
  EXPECT_TRUE(cell.plc().set_mode(RunMode::Run));
  cell.plc().scan(0);
  return cell.plc().read(parse_address("R4128"), 8);
}

// 2024-01-01T00:00:00, a Monday: second, minute, hour, day, month, year, week, hour:minute.
const std::vector<uint32_t> kDocumentedInstant = {0, 0, 0, 1, 1, 24, 1, 0};

int64_t seconds_of(const std::vector<uint32_t>& r) {
  return temp::to_seconds({int(2000 + r[5]), int(r[4]), int(r[3]), int(r[2]), int(r[1]), int(r[0])});
}

int64_t host_local_seconds() {
  const std::time_t now = std::time(nullptr);
  std::tm tm{};
  localtime_r(&now, &tm);
  return temp::to_seconds({tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday, tm.tm_hour, tm.tm_min, tm.tm_sec});
}

CellOverrides rtc_start(const std::string& v) {
  CellOverrides o;
  o.run.push_back({"", "rtc_start", {v}, "--rtc-start"});
  return o;
}

}  // namespace

TEST(CellClock, EveryVirtualTimeCellStartsAtTheDocumentedInstant) {
  TempDir d;
  const std::string cfg = write_cell(d);
  for (const Cell::Purpose p : {Cell::Purpose::Simulate, Cell::Purpose::Check}) {
    Cell cell(cfg, {}, p);
    EXPECT_EQ(clock_at_scan_1(cell), kDocumentedInstant);
  }
  CellOverrides node_in_virtual_time;  // plc_node ~virtual_time
  node_in_virtual_time.virtual_time = true;
  Cell served(cfg, node_in_virtual_time, Cell::Purpose::Serve);
  EXPECT_EQ(clock_at_scan_1(served), kDocumentedInstant);
  CellOverrides lockstep;
  lockstep.run.push_back({"", "engine", {"lockstep"}, "--engine"});
  Cell both(cfg, lockstep, Cell::Purpose::Simulate);
  EXPECT_EQ(clock_at_scan_1(both), kDocumentedInstant);
  EXPECT_EQ(both.twin()->plc().read(parse_address("R4128"), 8), kDocumentedInstant);
}

TEST(CellClock, ARealTimeCellReadsTheHostsClock) {
  TempDir d;
  Cell cell(write_cell(d), {}, Cell::Purpose::Serve);
  const int64_t before = host_local_seconds();
  const int64_t rtc = seconds_of(clock_at_scan_1(cell));
  const int64_t after = host_local_seconds();
  EXPECT_GE(rtc, before);
  EXPECT_LE(rtc, after);
}

TEST(CellClock, TheCellsStartAndTheOptionSayOtherwise) {
  TempDir d;
  const std::string own = write_cell(d, "modules:\n  rtc: {start: 2026-01-01T23:59:58}\n");
  Cell cell(own, {}, Cell::Purpose::Simulate);
  EXPECT_EQ(clock_at_scan_1(cell), (std::vector<uint32_t>{58, 59, 23, 1, 1, 26, 4, 0x173B}));
  Cell option(own, rtc_start("2030-06-15T12:30:05"), Cell::Purpose::Simulate);  // Saturday
  EXPECT_EQ(clock_at_scan_1(option), (std::vector<uint32_t>{5, 30, 12, 15, 6, 30, 6, 0x0C1E}));
  Cell host(own, rtc_start("host"), Cell::Purpose::Simulate);
  const int64_t before = host_local_seconds();
  const int64_t rtc = seconds_of(clock_at_scan_1(host));
  EXPECT_GE(rtc, before);
  EXPECT_LE(rtc, host_local_seconds());
}

TEST(CellClock, ABadStartIsRefusedNamingTheOption) {
  TempDir d;
  try {
    Cell cell(write_cell(d), rtc_start("2030-13-01T00:00:00"), Cell::Purpose::Simulate);
    FAIL() << "built";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()),
              "--rtc-start 2030-13-01T00:00:00: expected host or a date-time 2000-01-01T00:00:00 .. "
              "2099-12-31T23:59:59");
  }
}
