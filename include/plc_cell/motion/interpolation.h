#pragma once
// FUN147 MHSP0: linear interpolation of up to four axes in virtual time
// (docs/motion.md "FUN147"). Every LIN step starts all its axes at one instant and
// ends them at one instant: each axis runs the lead axis's profile scaled by its
// stroke, so its pulses are exact and its last pulse falls on the common end.
// Owned by the MotionUnit, which advances it with its own event loop.
#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/status_block.h"
#include "plc_cell/motion/axis.h"
#include "plc_cell/motion/lin_table.h"
#include "plc_cell/motion/profile.h"

namespace plc_cell {

class Memory;

namespace motion {

class MotionUnit;

struct Fun147Call {
  int gp = 0;
  Address sr{}, wr{};
  bool en = false, pau = false, abt = false;
  uint32_t instance = 0;
};
struct Fun147Outputs {
  bool act = false, err = false, dn = false;
};

class Interpolation {
 public:
  Interpolation(MotionUnit& unit, Memory& mem) : unit_(unit), mem_(mem) {}

  Fun147Outputs fun147(const Fun147Call& c, uint64_t t_ns);
  void advance(uint64_t t);  // to t, event by event (step ends, WAIT times)
  uint64_t next_event_ns() const;
  // M1934/M1935, DR4068/DR4070, D4062/D4063. With no group, and the block as it was last
  // written, the write would store the same bytes: inline, so that an idle unit's scan
  // compares without a call.
  void write_status(uint64_t t) {
    // Element by element: std::array's == calls memcmp, a call for two bytes.
    if (groups_.empty() && finished_[0] == written_finished_[0] && finished_[1] == written_finished_[1] &&
        written_.holds(mem_))
      return;
    rewrite_status(t);
  }
  void on_stop();
  bool idle() const { return groups_.empty(); }  // no FUN147 group to advance
  // FUN142 PSOFF on axis ps: the group driving it stops as on EN off (M1991 decides how).
  void psoff(int ps, uint64_t t);

  // Every group step completion with its exact instant (tests).
  using StepObserver = std::function<void(int gp, int step, uint64_t t_ns)>;
  void on_step_done(StepObserver f) { obs_.push_back(std::move(f)); }
  // Live vector speed of a group, Hz: sqrt of the sum of its axes' squared frequencies.
  double vector_speed(int gp, uint64_t t) const;

 private:
  enum class Phase { Idle, Moving, Waiting, SpeedWait, Paused, Stopping, Done };
  struct Group {
    Fun147Call call;
    LinTable table;
    Phase phase = Phase::Idle, after_stop = Phase::Idle;
    int step = 0;
    uint64_t wait_until = UINT64_MAX;
    uint8_t held = 0;          // axes taken for the run
    uint8_t moving = 0;        // axes of the present move
    std::array<int64_t, 4> rest{};  // logical pulses left per axis (signed) after a pause/cut
    double vspeed = 0;         // commanded vector speed of the step, Hz
    double acc = 0;            // vector acceleration of the move, Hz/s (speed / P13)
    std::array<double, 4> scale{};  // axis speed per vector speed: |d_n| / |d|
    bool chain = false;        // inside a LINE chain
    double chain_v = 0;        // vector speed at the end of the previous LINE step
    bool prev_pau = false, armed = true, dn = false, err = false;
  };

  uint32_t owner(const Group& g) const { return 0x40000000u | g.call.instance; }
  void advance(Group& g, uint64_t t);
  uint64_t next_event(const Group& g) const;
  uint64_t move_end(const Group& g) const;
  void start_step(Group& g, int k, uint64_t t);
  void start_move(Group& g, const LinStep& s, uint64_t t);
  // Starts the linear move of delta[n] logical pulses per axis at vector speed v.
  void move(Group& g, const std::array<int64_t, 4>& delta, double v, double v_in, bool line, uint64_t t);
  void step_done(Group& g, uint64_t t);
  void transfer(Group& g, uint64_t t);
  void go_to(Group& g, int target, uint64_t t);
  void stop(Group& g, uint64_t t, Phase then);
  void cut(Group& g, uint64_t t);
  void fail(Group& g, int code, uint64_t t);
  void release(Group& g);
  bool load(Group& g);
  void write_wr(Group& g);
  void rewrite_status(uint64_t t);

  MotionUnit& unit_;
  Memory& mem_;
  std::map<uint32_t, Group> groups_;  // by FUN147 instance
  std::array<bool, 2> finished_{};    // M1934 / M1935
  // The block as last written with no group: skipped while it still holds (status_block.h).
  static constexpr uint32_t kVectorReg = 4068;       // DR4068+2gp: vector speed (R4068..R4071)
  static constexpr uint32_t kGroupDoneRelay = 1934;  // M1934+gp: the group finished its last step
  StatusBlock<4, 2> written_{Area::R, kVectorReg, Area::M, kGroupDoneRelay};
  std::array<bool, 2> written_finished_{};
  std::vector<StepObserver> obs_;
};

}  // namespace motion
}  // namespace plc_cell
