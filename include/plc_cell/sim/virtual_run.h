#pragma once
// Runs a Plc in virtual time: a fixed number of scans of a fixed period, with
// every change of the watched addresses reported at its virtual time, and (on
// request) the events between the scans at their exact instants: interrupt entries,
// FUN140 step ends, CV=PV matches, homing phase changes.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {

struct WatchChange {
  uint64_t t_us;
  size_t watch;  // index into the watch list
  uint32_t value;
};

// How a watched value is printed (docs/command-line.md "plc_cell sim").
// Default: registers signed (16 or 32 bits as the address reads), bits and
// discrete groups (WX8, DWM0) unsigned.
enum class ValueFormat { Default, Signed, Unsigned, Hex, F32 };
int value_bits(const Address& a);  // 1, 16 or 32: what one read of the address gives
// "R1:u" -> ("R1", Unsigned); "R1" -> ("R1", Default). Suffixes: s, u, hex, f32.
// Throws Error for an unknown suffix.
std::pair<std::string, ValueFormat> split_format(const std::string& watch);
// Throws Error when the format does not fit the address (f32 on 16 bits, a bit).
void check_format(const Address& a, ValueFormat f, const std::string& text);
std::string format_value(const Address& a, uint32_t v, ValueFormat f);

// An event between two scans (or at a scan's instant), to the nanosecond.
struct SimEvent {
  uint64_t t_ns;
  std::string kind;    // interrupt, step_end, cv=pv, homing
  std::string source;  // HSC0I / PSO0 step 2 / HSC0 / PSO0 creep
};

class VirtualRun {
 public:
  VirtualRun(Plc& plc, uint64_t scan_period_us) : plc_(plc), period_us_(scan_period_us) {}

  size_t watch(const Address& a);
  // Collect events from the engine's counters and axes (if it has them).
  void trace_events();
  // Scans at t = now, now + period, ... while t < now + duration (so 2.5 s at 1 ms is 2500 scans).
  // The events a scan brings (those up to its instant) are reported before its changes.
  void run_for(uint64_t duration_us, const std::function<void(const WatchChange&)>& on_change = {},
               const std::function<void(const SimEvent&)>& on_event = {});
  std::vector<uint32_t> values() const;
  uint64_t now_us() const { return now_us_; }
  uint64_t scans() const { return scans_; }

 private:
  void report_events(const std::function<void(const SimEvent&)>& on_event);

  Plc& plc_;
  uint64_t period_us_;
  uint64_t now_us_ = 0;
  uint64_t scans_ = 0;
  std::vector<Address> watches_;
  std::vector<uint32_t> last_;
  std::vector<bool> seen_;
  // Shared with the observers registered in the units (they outlive this run).
  std::shared_ptr<std::vector<SimEvent>> events_ = std::make_shared<std::vector<SimEvent>>();
};

}  // namespace plc_cell
