#pragma once
// The sink end of a wire, in the cell it drives: the source's changes, as the wire's delay
// line turns them into timed edges (delay_line.h), into the cell at their instants:
//   * an input X0-X15: exact edges of the cell's simulation (sim/simulated_cell.h), so a
//     counter or an edge interrupt sees each at its instant, between scans too;
//   * another input: a signal of the cell's simulation, sampled at each scan (the level of
//     the last edge at or before the scan's instant; a capture input sees a pulse between
//     two scans);
//   * a relay (M, S) or a register (R, D): written before the scan, as a client writes it.
// A scenario's set (or a ROS topic) on a wired input takes it from the wire, and a simulate
// step gives it back, as for the cell's own simulated inputs. The wire is not written
// again until its next edge: a write to a wired relay or register holds until then.
#include <cstdint>
#include <memory>

#include "plc_cell/core/address.h"
#include "plc_cell/line/delay_line.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {
namespace line {

class WireSink {
 public:
  // Inside soft.plc().locked(), which gives e and mem: the cell's input (or memory) holds
  // the wire's initial value from the first scan on.
  static std::unique_ptr<WireSink> make(SoftCell& soft, ScanEngine& e, Memory& mem, const Address& to,
                                        const WireModel& m, uint32_t initial);
  virtual ~WireSink() = default;

  // With the PLC's lock held: the source's value, sampled at t_us of this cell's clock (in
  // virtual time the line's one clock, the source's scan; in real time the sink's
  // ScanEngine::now_us() when the value arrives).
  void receive(uint64_t t_us, uint32_t value) {
    edges_.clear();
    delay_.sample(t_us, value, &edges_);
    for (const WireEdge& e : edges_) put(e);
  }

 protected:
  WireSink(const WireModel& m, uint32_t initial) : delay_(m, initial) {}
  virtual void put(const WireEdge& e) = 0;
  const DelayLine& delay() const { return delay_; }

 private:
  DelayLine delay_;
  std::vector<WireEdge> edges_;
};

}  // namespace line
}  // namespace plc_cell
