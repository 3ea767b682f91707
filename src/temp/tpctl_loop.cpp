// The loop machinery shared by FUN86 (FBs, FB) and FUN73: see tpctl_loop.h.
#include "plc_cell/temp/tpctl_loop.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/interpreter.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/temp/temperature_cell.h"
#include "set_output.h"

namespace plc_cell {
namespace temp {
OperandRule tpctl_outputs_rule(size_t yn, size_t zn, int64_t zn_max, const std::string& zn_name) {
  return {"Yn: " + zn_name + " outputs within Y0-Y255", [=](const OperandValues& v) {
            return v[zn] < 1 || v[zn] > zn_max || v.y_fit(yn, uint32_t(v[zn]));
          }};
}

OperandRule tpctl_tables_rule(size_t tables, size_t zn, int64_t zn_max, const std::string& zn_name) {
  return {"Sv, Os, PR, IR, DR and OR: " + zn_name + " registers each", [=](const OperandValues& v) {
            if (v[zn] < 1 || v[zn] > zn_max) return true;  // the count's own rule says so
            for (size_t k = tables; k < tables + 6; ++k)
              if (!v.words_fit(k, uint32_t(v[zn]))) return false;
            return true;
          }};
}

void tpctl_outputs_off(TpctlLoopState& st, const BoundOperand& yn, uint32_t n, bool restart) {
  for (uint32_t i = 0; i < n; ++i) set_y(yn, i, false);
  if (restart) st.active = false;
}

TpctlResult tpctl_step(TpctlLoopState& st, ExecContext& c, const TpctlUnits& u, const TpctlTables& t,
                       uint32_t first_point, uint32_t n, bool heating, int method) {
  Memory& mem = c.mem;
  const uint64_t now = c.now_us;
  // A new RUN (or a new clock) starts the loop afresh, as EN rising does.
  if (mem.bit(Area::M, special::kFirstScan) || now < st.last_us) st.active = false;
  st.last_us = now;
  if (!st.active) {
    const uint16_t r4005 = mem.reg(Area::R, treg::kIntervals);
    st.ts_us = u.interval_us(r4005 & 0xFF);
    st.ts_tenths = int(st.ts_us / 100000);
    st.cycle_us = u.interval_us(r4005 >> 8);
    st.points.assign(n, {});
    for (auto& p : st.points) p.full_scale = u.full_scale;
    st.duty.assign(n, 0.0);
    st.high_count.assign(n, 0);
    st.large_since.assign(n, now);
    st.next_solve = now;
    st.cycle_start = now;
    st.active = true;
    // Defaults on the first execution, into registers the program left at 0.
    for (uint32_t i = 0; i < n; ++i) {
      if (t.pr.w[i] == 0) t.pr.w[i] = u.kc0;
      if (t.ir.w[i] == 0) t.ir.w[i] = u.ki0;
      if (t.dr.w[i] == 0) t.dr.w[i] = u.td0;
    }
  }
  const uint32_t enable = mem.reg(Area::R, treg::kPidEnable) | uint32_t(mem.reg(Area::R, treg::kPidEnable + 1)) << 16;
  const bool solve = now >= st.next_solve;
  if (solve) st.next_solve += st.ts_us * ((now - st.next_solve) / st.ts_us + 1);
  bool cycle_begins = solve;  // a new output takes effect at once
  if (now >= st.cycle_start + st.cycle_us) {
    st.cycle_start += st.cycle_us * ((now - st.cycle_start) / st.cycle_us);
    cycle_begins = true;
  }

  TpctlResult r;
  const int large_pct = std::clamp<int>(mem.reg(Area::R, treg::kLargePower), 80, 100);
  const uint64_t large_us =
      uint64_t(std::max<uint16_t>(mem.reg(Area::R, treg::kLargePowerTime), u.large_time_min_s)) * 1000000;
  const int32_t high = mem.reg(Area::R, treg::kHighAlarm) * u.zone_per_degree;
  const double fs = u.full_scale;
  for (uint32_t i = 0; i < n; ++i) {
    const TpctlPv& pv = st.pv[i];
    const int32_t spv = int16_t(t.sv.w[i]), off = int16_t(t.os.w[i]);
    if (!(enable >> (first_point + i) & 1u)) {  // PID disabled for this point: its output is OFF
      set_y(t.yn, i, false);
      st.points[i] = {};
      st.points[i].full_scale = fs;
      continue;
    }
    TpctlPoint& p = st.points[i];
    if (solve) {
      const int kc = std::clamp<int>(t.pr.w[i], 1, u.gain_max), ki = std::min<int>(t.ir.w[i], u.gain_max),
                td = std::min<int>(t.dr.w[i], u.gain_max);
      t.out.w[i] = static_cast<uint16_t>(
          std::lround(p.solve(pv.pid_sv, pv.pid_pv, kc, ki, td, st.ts_tenths, heating, method)));
    }
    if (cycle_begins) st.duty[i] = std::min(double(t.out.w[i]), fs) / fs;
    set_y(t.yn, i, double(now - st.cycle_start) < st.duty[i] * double(st.cycle_us));

    const bool zone = pv.zone_pv >= spv - off && pv.zone_pv <= spv + off;
    if (zone) r.in_zone |= 1u << i;
    else r.alarm = true;
    // High temperature: PV >= R4008 on ten successive executions.
    st.high_count[i] = pv.zone_pv >= high ? uint8_t(std::min(st.high_count[i] + 1, 10)) : 0;
    // Heater open / aged: output at "large power" for R4007 s without reaching the zone.
    const bool big = t.out.w[i] * 100.0 >= large_pct * fs;
    if (!big || zone) st.large_since[i] = now;
    if (st.high_count[i] >= 10 || now - st.large_since[i] >= large_us) r.warn |= 1u << i, r.alarm = true;
  }
  return r;
}

}  // namespace temp
}  // namespace plc_cell
