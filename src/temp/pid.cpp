// FUN30 PID: position-form PID on a raw analog measurement, scaled to engineering
// units for the alarms, with auto/manual, bumpless transfer, direct/reverse action,
// integral wind-up limits and a solution interval timed by the 1 ms cyclic timer.
#include "plc_cell/temp/pid.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace temp {
namespace {

using R = OperandRole;
constexpr double kFull = 16383;

// WR+0 status bits (A:7578).
constexpr uint16_t kAuto = 1u << 0, kSolved = 1u << 1, kBumpless = 1u << 2, kErr = 1u << 4, kHal = 1u << 5,
                   kLal = 1u << 6;

int32_t s16(uint16_t v) { return int16_t(v); }

constexpr size_t kPidOperands = 8;  // Ts SR OR PR WR ERR HAL LAL

// Ts, often a constant: what `check` can tell before the first scan. The settings in
// SR and PR are register contents, known at run time only.
const OperandRules& pid_rules() {
  static const OperandRules r = {
      {"1 <= Ts <= 3000 (0.01 s)", [](const OperandValues& v) { return v[0] >= 1 && v[0] <= 3000; }},
  };
  return r;
}

// The settings blocks SR (A:7530-A:7560) and PR, and the D4004/D4005 options.
struct Settings {
  int32_t sp, hal, lal, her, ler, ram, opv, rmax;
  int32_t pb, ki, td, bias, hiwl, liwl, method, gain;
};

Settings read_settings(Memory& mem, const uint16_t* sr, const uint16_t* pr) {
  Settings s;
  s.sp = s16(sr[1]), s.hal = s16(sr[2]), s.lal = s16(sr[3]);
  s.her = s16(sr[4]), s.ler = s16(sr[5]);
  s.ram = sr[6], s.opv = sr[7];
  s.rmax = mem.reg(Area::D, 4004) == 1 ? 16383 : 16380;
  s.pb = pr[0], s.ki = pr[1], s.td = pr[2], s.bias = pr[3], s.hiwl = pr[4], s.liwl = pr[5], s.method = pr[6];
  // D4005, the gain constant (default 1000): a cleared register counts as the default.
  s.gain = mem.reg(Area::D, 4005) == 0 ? 1000 : mem.reg(Area::D, 4005);
  return s;
}

// Anything out of range: no PID, ERR on.
bool settings_ok(const Settings& s) {
  return s.her > -9999 && s.her <= 19999 && s.ler >= -9999 && s.ler <= s.lal && s.lal < s.hal &&
         s.hal <= s.her && s.sp >= s.ler && s.sp <= s.her && s.ram >= 0 && s.ram <= s.rmax && s.opv >= 0 &&
         s.opv < s.rmax && s.pb >= 1 && s.pb <= 5000 && s.ki >= 0 && s.ki <= 9999 && s.td >= 0 && s.td <= 9999 &&
         s.bias >= 0 && s.bias <= 16383 && s.hiwl >= 1 && s.hiwl <= 16383 && s.liwl >= 0 && s.liwl <= 16383 &&
         s.liwl < s.hiwl && (s.method == 0 || s.method == 1) && s.gain >= 1 && s.gain <= 5000;
}

void run_pid(ExecContext& c, const BoundOperand* o) {
  const bool autom = c.inputs[0], bum = c.inputs[1], direct = c.inputs[2];
  const int64_t ts = c.get(o[0]);
  uint16_t* sr = o[1].w;
  const BoundOperand& out = o[2];
  uint16_t* pr = o[3].w;
  uint16_t* wr = o[4].w;
  const BoundOperand &err = o[5], &hal = o[6], &lal = o[7];

  const Settings s = read_settings(c.mem, sr, pr);
  const bool ok = !broken_rule(pid_rules(), OperandValues(c, o, kPidOperands)) && settings_ok(s);
  uint16_t status = wr[0] & (kAuto | kBumpless);
  c.flag(err, !ok);
  if (!ok) {
    wr[0] = status | kErr;
    c.flag(hal, false);
    c.flag(lal, false);
    return;
  }
  // Scaled PV (SR+0): LER + (RAM - OPV)(HER - LER)/(Rmax - OPV), RAM below OPV reads LER.
  const double span = double(s.rmax - s.opv);
  const double raw = std::max(0, s.ram - s.opv);
  const int32_t pv_eng = int32_t(std::lround(s.ler + raw * (s.her - s.ler) / span));
  sr[0] = uint16_t(int16_t(pv_eng));
  const bool hi = pv_eng >= s.hal, lo = pv_eng <= s.lal;  // whatever A/M is
  c.flag(hal, hi);
  c.flag(lal, lo);
  if (hi) status |= kHal;
  if (lo) status |= kLal;

  const uint16_t now_ms = uint16_t(c.now_us / 1000);  // the 1 ms cyclic timer
  int32_t isum = int32_t(uint32_t(wr[2]) | uint32_t(wr[3]) << 16);  // integral, 0.01 output counts
  if (!autom) {
    // Manual: the program writes OR; the loop tracks PV so that auto starts cleanly.
    wr[0] = uint16_t((status & ~(kAuto | kBumpless)) | (bum ? kBumpless : 0));
    wr[4] = uint16_t(s.ram);
    return;
  }
  const bool entering = !(wr[0] & kAuto);
  const bool due = entering || uint16_t(now_ms - wr[1]) >= 10 * ts;
  status = uint16_t((status | kAuto) & ~kBumpless) | (bum ? kBumpless : 0);
  if (!due) {
    wr[0] = status;
    return;
  }
  // The error on the raw scale, normalised so that the span is full scale:
  // Pb 100 % (1000) with D4005 1000 (Kc 1) turns a full-span error into full output.
  const double kc = double(s.gain) / s.pb;
  const double sp_raw = (s.sp - s.ler) * span / double(s.her - s.ler);
  const double sign = direct ? 1.0 : -1.0;  // D/R = 1: output rises with the error
  const double e = sign * (sp_raw - raw) * kFull / span;
  const double dpv = entering ? 0.0 : sign * (raw - (double(wr[4]) - s.opv)) * kFull / span;
  const double p = kc * e;
  const double d = -kc * 60.0 * s.td * dpv / ts;  // Td/100 min over Ts/100 s
  if (entering) isum = bum ? int32_t(std::lround((double(c.get(out)) - p - d - s.bias) * 100)) : 0;
  const double di = kc * e * s.ki * ts / 600000.0;  // Ki/100 repeats/min over Ts/100 s
  const double free = p + d + s.bias;
  const double m0 = free + isum / 100.0;
  // Wind-up limits (HIWL/LIWL): no integration that pushes the output past them.
  // Method 1 (minimum overshoot): integrate only inside the proportional band.
  const bool in_band = free > 0 && free < kFull;
  const bool windup = (m0 >= s.hiwl && di > 0) || (m0 <= s.liwl && di < 0);
  if (!entering && !windup && (s.method == 0 || in_band)) isum += int32_t(std::lround(di * 100));
  isum = std::clamp<int32_t>(isum, -int32_t(kFull) * 100, int32_t(kFull) * 100);
  const double m = std::clamp(free + isum / 100.0, 0.0, kFull);
  c.put(out, std::lround(m));
  wr[0] = status | kSolved;
  wr[1] = now_ms;
  wr[2] = uint16_t(uint32_t(isum));
  wr[3] = uint16_t(uint32_t(isum) >> 16);
  wr[4] = uint16_t(s.ram);
}

}  // namespace

void add_pid_function(FunctionTable& t) {
  FunctionSpec s;
  s.number = 30;
  s.mnemonic = "PID";
  s.inputs = {"AM", "BUM", "DR"};
  s.operands = {{"Ts", R::Source},         {"SR", R::Register, false, 8}, {"OR", R::Dest},
                {"PR", R::Register, false, 7}, {"WR", R::Register, false, 5}, {"ERR", R::BitOut, true},
                {"HAL", R::BitOut, true},  {"LAL", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // manual mode (A/M = 0) still scales PV and drives HAL/LAL
  s.rules = pid_rules();
  s.handler = [](ExecContext& c, const BoundOperand* o) {
    // WR+0 bit 1 is on only in the scan the loop is solved.
    o[4].w[0] &= uint16_t(~kSolved);
    run_pid(c, o);
  };
  t.add(s);
}

}  // namespace temp
}  // namespace plc_cell
