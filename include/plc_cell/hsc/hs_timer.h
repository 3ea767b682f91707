#pragma once
// The high-speed timers of the FBs-PLC: HST0-HST3 (HSC0-HSC3 configured as timers,
// 0.1 ms ticks, interrupt at CV=PV) and HSTA (a free-running 0.1 ms timer, or a periodic
// interrupt every PV ticks). Their CV is a function of the time since the last write,
// so they cost nothing between their events.
#include <cstdint>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

constexpr uint64_t kTimerTick = 100000;  // 0.1 ms in ns

// What a timer keeps between writes: its CV is cv0 plus the ticks since base.
struct TimerState {
  uint32_t pv = 0;
  uint32_t cv0 = 0;
  uint64_t base = 0;
  void restart(uint64_t t_ns) { *this = TimerState{0, 0, t_ns}; }
};

class HsTimer final : public Component {
 public:
  HsTimer(UnitContext& ctx, int n) : ctx_(ctx), n_(n) {}

  void start(uint64_t t_ns) override { s_.restart(t_ns); }
  uint64_t next_event_ns() override;
  void at(uint64_t t_ns) override;

  uint32_t cv(uint64_t t_ns) const { return s_.cv0 + static_cast<uint32_t>((t_ns - s_.base) / kTimerTick); }
  void preset(uint32_t v);          // counts on from v now
  void read_chip();                 // FUN92
  void write_chip(bool pv);         // FUN93

 private:
  UnitContext& ctx_;
  int n_;
  TimerState s_;
  uint64_t match_ = kNever;
};

class HstaTimer final : public Component {
 public:
  explicit HstaTimer(UnitContext& ctx) : ctx_(ctx) {}

  void start(uint64_t t_ns) override { s_.restart(t_ns); }
  uint64_t next_event_ns() override;
  void at(uint64_t t_ns) override;

  void read_chip();                 // FUN92 CN=4
  void write_chip(bool pv);         // FUN93 CN=4

 private:
  UnitContext& ctx_;
  TimerState s_;                    // pv: R4154, 0 for a free-running timer
  uint64_t next_ = kNever;
};

// The time-base interrupts 1MSI ... 100MSI: the smallest one present and not masked in
// R4162 ticks from RUN.
class TimeBaseInterrupt final : public Component {
 public:
  explicit TimeBaseInterrupt(UnitContext& ctx) : ctx_(ctx) {}

  void start(uint64_t t_ns) override { run_ns_ = t_ns; }
  uint64_t next_event_ns() override;
  void at(uint64_t t_ns) override;

 private:
  int active() const;

  UnitContext& ctx_;
  uint64_t run_ns_ = 0;             // when RUN started: the time bases count from here
  int tb_ = -1;
  uint64_t next_ = kNever;
};

}  // namespace hsc
}  // namespace plc_cell
