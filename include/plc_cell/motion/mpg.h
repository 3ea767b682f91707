#pragma once
// FUN148 MPG: a manual pulse generator (handwheel) counted by an HSC drives an axis
// (docs/motion.md "FUN148"). Each execution (normally in a 50 ms time-base ISR)
// samples the counter and sends (input pulses x Fa + remainder) / Fb pulses at Fo
// with the axis's P4/P8 ramps; the remainder of the division is kept so that no
// pulse is lost over many executions.
#include <cstdint>
#include <map>

#include "plc_cell/core/address.h"

namespace plc_cell {

class Memory;
namespace hsc {
class HscUnit;
}

namespace motion {

class MotionUnit;

struct Fun148Call {
  int sc = 0, ps = 0;        // source HSC 0-7, axis 0-3
  int64_t fo = 0;            // output speed, Hz (32-bit)
  int64_t fa = 1, fb = 1;    // multiplier Fa / Fb (Mr+0, Mr+1)
  Address wr{};              // 4 working registers
  bool en = false;
  uint32_t instance = 0;
};

class Mpg {
 public:
  static constexpr uint32_t kLimitReg = 4020;  // R4020: high byte 55H enables the travel limits

  Mpg(MotionUnit& unit, Memory& mem, hsc::HscUnit* counters) : unit_(unit), mem_(mem), hsc_(counters) {}

  bool fun148(const Fun148Call& c, uint64_t t_ns);  // returns ACT
  void advance(uint64_t t);                         // frees an axis whose MPG output has ended
  uint64_t next_event_ns() const;
  void on_stop() { st_.clear(); }
  bool idle() const { return st_.empty() || !holding(); }  // no FUN148 output holds an axis
  // FUN142 PSOFF on axis ps: an MPG output on it stops (M1991: decelerating to P5) and
  // its undelivered input is dropped.
  void psoff(int ps, uint64_t t);

 private:
  struct State {
    bool primed = false;  // the first execution only takes the counter's value
    uint32_t last_cv = 0;
    int64_t rem = 0;      // (input x Fa) not yet sent, in 1/Fb pulses
    int ps = -1;
    bool holding = false;
  };
  bool holding() const;
  uint32_t owner(uint32_t instance) const { return 0x20000000u | instance; }
  uint32_t counter_value(int sc) const;
  void output(State& s, const Fun148Call& c, int64_t pulses, uint64_t t);
  void release(State& s, uint32_t instance);

  MotionUnit& unit_;
  Memory& mem_;
  hsc::HscUnit* hsc_;
  std::map<uint32_t, State> st_;  // by FUN148 instance
};

}  // namespace motion
}  // namespace plc_cell
