#pragma once
// The source ends of the wires that leave one cell: after each of its scans, whoever scans
// it (the line's virtual clock, a real-time scan thread) reads every wire's address in the
// same memory copy and keeps the changes, each with the scan's instant, until the carrier
// takes them to the sink ends (wire_sink.h). Only changes travel: a wire that holds its
// value costs one read per scan.
#include <cstdint>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace line {

class WireTaps {
 public:
  struct Sample {
    size_t tap;     // the index add() gave
    uint64_t t_us;  // the instant of the scan it ended
    uint32_t value;
  };

  // A tap on a, whose value before the first scan is initial; its index.
  size_t add(const Address& a, uint32_t initial) {
    taps_.push_back({a, a.width == Width::Bit, initial});
    return taps_.size() - 1;
  }
  size_t size() const { return taps_.size(); }
  // With the PLC's lock held, right after the scan at t_us.
  void sample(const Memory& m, uint64_t t_us) {
    for (size_t i = 0; i < taps_.size(); ++i) {
      const uint32_t v = taps_[i].bit ? uint32_t(m.bit(taps_[i].a.area, taps_[i].a.index)) : m.read(taps_[i].a);
      if (v == taps_[i].last) continue;
      taps_[i].last = v;
      pending_.push_back({i, t_us, v});
    }
  }
  // The changes sampled since the carrier last cleared them, in order.
  std::vector<Sample>& pending() { return pending_; }

 private:
  struct Tap {
    Address a;
    bool bit;
    uint32_t last;
  };
  std::vector<Tap> taps_;
  std::vector<Sample> pending_;
};

}  // namespace line
}  // namespace plc_cell
