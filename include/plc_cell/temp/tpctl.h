#pragma once
// FUN86 TPCTL, the FBs temperature PID (manual A:7043-A:7200), as plain math on one
// point, and its registration. docs/analog-and-temperature.md gives the unit choices
// the manual leaves open.
#include <cstdint>

namespace plc_cell {

class FunctionTable;

namespace temp {

// One point's controller. Units as the registers hold them: PV and SV in 0.1 degree,
// Kc 1..9999 (output counts per 0.1 degree), Ki 0.01 repeats/min, Td 0.01 min,
// Ts 0.1 s; output 0..16383.
struct TpctlPoint {
  double integral = 0;  // output counts
  int32_t prev_pv = 0;
  bool primed = false;  // prev_pv valid
  double output = 0;
  double full_scale = 16383;  // output range: 16383 (FBs FUN86), 4095 (FB FUN73/FUN86)

  // One solve. heating: error SV - PV (cooling: PV - SV); the derivative acts on PV
  // with the sign that opposes its change (the manual's "+" is taken as a typo, §16).
  // method 0 (modified minimum overshoot): the integral only runs inside the
  // proportional band; method 1 (universal): always, with conditional-integration
  // anti-windup in both.
  double solve(int32_t sv, int32_t pv, int kc, int ki, int td, int ts_tenths, bool heating, int method);
};

constexpr int kTpctlFullScale = 16383;

// Adds FUN86 TPCTL (the FBs version) to t.
void add_tpctl_function(FunctionTable& t);

// R4005 byte -> period, FBs codes: 0 = 1 s, 1 = 2 s, 2 = 4 s ... >= 5 = 32 s.
uint64_t fbs_interval_us(unsigned code);

}  // namespace temp
}  // namespace plc_cell
