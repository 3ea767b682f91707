#pragma once
// An analytic signal source of the simulated cell: an encoder (phases A and B) or
// a pulse generator (phase A only) whose position is exact rational arithmetic in
// virtual time, so edges between two scans are counted, not sampled.
//
// Position p is kept in pico-cycles (1e-12 of a period); the rate in milli-hertz,
// so p(t) = p0 + (t_ns - t0) * rate_mhz exactly. The quarter index Q = floor(4p/1e12)
// fixes the levels: A = 1 for Q mod 4 in {0,1}, B = 1 for Q mod 4 in {1,2} (A leads
// B when the rate is positive). A pulse generator uses A only: one rising edge per
// period, 50 % duty.
#include <cstdint>
#include <string>

#include "plc_cell/hsc/edge_source.h"

namespace plc_cell {
namespace hsc {

class PulseSource : public EdgeSource {
 public:
  PulseSource(std::string name, int pin_a, int pin_b) : name_(std::move(name)), pin_a_(pin_a), pin_b_(pin_b) {}

  const std::string& name() const override { return name_; }
  int pin_a() const { return pin_a_; }
  int pin_b() const { return pin_b_; }  // -1 for a single-phase generator

  // From t_ns on, move at hz periods per second (negative: B leads A, backwards).
  void set_rate(uint64_t t_ns, double hz);
  double rate_hz() const override { return rate_mhz_ / 1000.0; }
  int direction() const override { return rate_mhz_ > 0 ? 1 : rate_mhz_ < 0 ? -1 : 0; }

  int64_t quarter(uint64_t t_ns) const override;
  static bool level_a(int64_t q) { return mod4(q) <= 1; }
  static bool level_b(int64_t q) { return mod4(q) == 1 || mod4(q) == 2; }
  // First time >= from_ns at which Q reaches q (>= q moving forward, <= q backward);
  // UINT64_MAX if it never does at the present rate.
  uint64_t time_of_quarter(int64_t q, uint64_t from_ns) const override;
  bool level(int phase, int64_t q) const override { return phase == 0 ? level_a(q) : level_b(q); }
  static int mod4(int64_t q) { return static_cast<int>(((q % 4) + 4) % 4); }

 private:
  std::string name_;
  int pin_a_, pin_b_;
  uint64_t t0_ = 0;
  __int128 p0_ = 0;
  int64_t rate_mhz_ = 0;
};

}  // namespace hsc
}  // namespace plc_cell
