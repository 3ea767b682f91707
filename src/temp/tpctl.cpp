// FUN86 TPCTL: PID temperature control of up to 32 points with time-proportional
// (PWM) outputs, in-zone bits, and high-temperature / heater-open warnings.
#include "plc_cell/temp/tpctl.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/interpreter.h"
#include "plc_cell/temp/temperature_cell.h"

namespace plc_cell {
namespace temp {

double TpctlPoint::solve(int32_t sv, int32_t pv, int kc, int ki, int td, int ts, bool heating, int method) {
  const double sign = heating ? 1.0 : -1.0;
  const double e = sign * double(sv - pv);
  const double p = kc * e;
  // Ki repeats/min x Ts: Ki/100 per 60 s, Ts/10 s  ->  Kc e Ki Ts / 60000 per solve.
  const double di = kc * e * ki * ts / 60000.0;
  // Td/100 min = 0.6 Td s; dPV per Ts/10 s  ->  Kc 6 Td dPV / Ts.
  const double d = primed ? -sign * kc * 6.0 * td * double(pv - prev_pv) / ts : 0.0;
  prev_pv = pv;
  primed = true;
  const double free = p + d;  // what the output would be without the integral
  const bool in_band = free > -kTpctlFullScale && free < kTpctlFullScale;
  if (method == 1 || in_band) {
    const double m = free + integral + di;
    // Conditional integration: no accumulation that drives a saturated output further.
    if (!((m > kTpctlFullScale && di > 0) || (m < 0 && di < 0))) integral += di;
  }
  integral = std::clamp(integral, -double(kTpctlFullScale), double(kTpctlFullScale));
  output = std::clamp(free + integral, 0.0, double(kTpctlFullScale));
  return output;
}

namespace {

using R = OperandRole;

struct Instance {
  bool active = false;          // EN was on at the previous execution
  uint64_t last_us = 0;
  uint64_t ts_us = 0, cycle_us = 0;
  int ts_tenths = 40;
  uint64_t next_solve = 0, cycle_start = 0;
  std::vector<TpctlPoint> points;
  std::vector<double> duty;     // latched at each PWM cycle start
  std::vector<uint8_t> high_count;
  std::vector<uint64_t> large_since;
  std::vector<uint8_t> large;
};

struct Store {
  std::mutex mu;
  std::map<std::pair<const Memory*, uint32_t>, Instance> by_key;
};

uint64_t interval_us(unsigned code) { return uint64_t(1000000) << std::min(code, 5u); }  // 1, 2, 4 .. 32 s

// The start of the PVs: R4004 when R4003 = A55AH, else the configured readings.
const uint16_t* pv_source(const Memory& mem, uint32_t needed, bool* ready) {
  *ready = true;
  if (mem.reg(Area::R, treg::kPvFromR4004) == 0xA55A) {
    const uint32_t a = mem.reg(Area::R, treg::kPvStart);
    if (a >= 10000 && a + needed <= 13840) return mem.words(Area::R) + (a - 10000);
    if (a >= 20000 && a + needed <= 24000) return mem.words(Area::D) + (a - 20000);
  }
  const TemperatureCell* cell = temperature_cell_of(mem);
  if (!cell) return nullptr;
  *ready = cell->all_read();  // FUN86 runs only after every channel has been read (A:7136)
  const Address& r = cell->config().readings;
  if (r.index + needed > Memory::word_count(r.area)) return nullptr;
  return mem.words(r.area) + r.index;
}

bool table_fits(const BoundOperand& o, uint32_t n) {
  return o.w && o.addr.index + n <= Memory::word_count(o.addr.area);
}

void set_y(const BoundOperand& y, uint32_t i, bool v) {
  uint8_t& c = y.b[i];
  if (!(c & kBitDisabled)) c = v ? kBitState : 0;
}

void run(Store& store, ExecContext& c, const BoundOperand* o) {
  Memory& mem = c.mem;
  const int md = int(c.get(o[0]));
  const BoundOperand& yn = o[1];
  const int64_t sn = c.get(o[2]), zn = c.get(o[3]);
  const bool heating = c.inputs[1];
  const BoundOperand &sv = o[4], &os = o[5], &pr = o[6], &ir = o[7], &dr = o[8], &out = o[9], &wr = o[10];
  const BoundOperand &err = o[11], &alm = o[12];

  std::lock_guard<std::mutex> lk(store.mu);
  Instance& st = store.by_key[{&mem, c.instance}];
  const bool shape_ok = md >= 0 && md <= 1 && sn >= 0 && sn <= 31 && zn >= 1 && zn <= 32 && sn + zn <= 32 &&
                        yn.addr.area == Area::Y && yn.addr.index + zn <= 256;
  const uint32_t n = shape_ok ? uint32_t(zn) : 0;
  const bool tables_ok = shape_ok && table_fits(sv, n) && table_fits(os, n) && table_fits(pr, n) &&
                         table_fits(ir, n) && table_fits(dr, n) && table_fits(out, n) && table_fits(wr, 9);
  bool ready = false;
  const uint16_t* pvs = tables_ok ? pv_source(mem, uint32_t(sn + zn), &ready) : nullptr;

  if (!c.en || !pvs) {
    // EN off (or an error): outputs off; the next EN = 1 takes R4005 afresh (Note 1).
    if (shape_ok)
      for (uint32_t i = 0; i < n; ++i) set_y(yn, i, false);
    st.active = false;
    c.flag(err, c.en && !pvs);
    if (c.en && !pvs) c.flag(alm, false);
    return;
  }
  c.flag(err, false);
  if (!ready) {
    for (uint32_t i = 0; i < n; ++i) set_y(yn, i, false);
    return;
  }
  const uint64_t now = c.now_us;
  // A new RUN (or a new clock) starts the loop afresh, as EN rising does.
  if (mem.bit(Area::M, special::kFirstScan) || now < st.last_us) st.active = false;
  st.last_us = now;
  if (!st.active) {
    const uint16_t r4005 = mem.reg(Area::R, treg::kIntervals);
    st.ts_us = interval_us(r4005 & 0xFF);
    st.ts_tenths = int(st.ts_us / 100000);
    st.cycle_us = interval_us(r4005 >> 8);
    st.points.assign(n, {});
    st.duty.assign(n, 0.0);
    st.high_count.assign(n, 0);
    st.large_since.assign(n, now);
    st.large.assign(n, 0);
    st.next_solve = now;
    st.cycle_start = now;
    st.active = true;
    // Defaults on the first execution (A:7129), into registers the program left at 0.
    for (uint32_t i = 0; i < n; ++i) {
      if (pr.w[i] == 0) pr.w[i] = 110;
      if (ir.w[i] == 0) ir.w[i] = 17;
      if (dr.w[i] == 0) dr.w[i] = 50;
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

  uint32_t in_zone = 0, warn = 0;
  bool alarm = false;
  const int large_pct = std::clamp<int>(mem.reg(Area::R, treg::kLargePower), 80, 100);
  const uint64_t large_us = uint64_t(std::max<uint16_t>(mem.reg(Area::R, treg::kLargePowerTime), 60)) * 1000000;
  const int32_t high = mem.reg(Area::R, treg::kHighAlarm);
  for (uint32_t i = 0; i < n; ++i) {
    const uint32_t point = uint32_t(sn) + i;
    const int32_t pv = int16_t(pvs[point]);
    const int32_t spv = int16_t(sv.w[i]), off = int16_t(os.w[i]);
    if (!(enable >> point & 1u)) {  // PID disabled for this point: its output is OFF
      set_y(yn, i, false);
      st.points[i] = {};
      continue;
    }
    TpctlPoint& p = st.points[i];
    if (solve) {
      const int kc = std::clamp<int>(pr.w[i], 1, 9999), ki = std::min<int>(ir.w[i], 9999),
                td = std::min<int>(dr.w[i], 9999);
      out.w[i] = static_cast<uint16_t>(std::lround(p.solve(spv, pv, kc, ki, td, st.ts_tenths, heating, md)));
    }
    if (cycle_begins) st.duty[i] = double(out.w[i] > kTpctlFullScale ? kTpctlFullScale : out.w[i]) / kTpctlFullScale;
    set_y(yn, i, double(now - st.cycle_start) < st.duty[i] * double(st.cycle_us));

    const bool zone = pv >= spv - off && pv <= spv + off;
    if (zone) in_zone |= 1u << i;
    else alarm = true;
    // High temperature: PV >= R4008 on ten successive executions.
    st.high_count[i] = pv >= high ? uint8_t(std::min(st.high_count[i] + 1, 10)) : 0;
    // Heater open / aged: output at "large power" for R4007 s without reaching the zone.
    const bool big = out.w[i] * 100 >= uint32_t(large_pct) * kTpctlFullScale;
    if (!big || zone) st.large_since[i] = now;
    const bool w = st.high_count[i] >= 10 || now - st.large_since[i] >= large_us;
    if (w) warn |= 1u << i, alarm = true;
  }
  wr.w[0] = uint16_t(in_zone);
  wr.w[1] = uint16_t(in_zone >> 16);
  wr.w[2] = uint16_t(warn);
  wr.w[3] = uint16_t(warn >> 16);
  wr.w[4] = uint16_t(st.ts_tenths);  // internal: the solution interval in use (0.1 s)
  c.flag(alm, alarm);
}

}  // namespace

void add_tpctl_function(FunctionTable& t) {
  auto store = std::make_shared<Store>();
  FunctionSpec s;
  s.number = 86;
  s.mnemonic = "TPCTL";
  s.inputs = {"EN", "HC"};
  s.operands = {{"Md", R::Const},     {"Yn", R::BitOut},   {"Sn", R::Const},    {"Zn", R::Const},
                {"Sv", R::Register},  {"Os", R::Register}, {"PR", R::Register}, {"IR", R::Register},
                {"DR", R::Register},  {"OR", R::Register}, {"WR", R::Register, false, 9},
                {"ERR", R::BitOut, true}, {"ALM", R::BitOut, true}};
  s.allow_32 = false;
  s.allow_pulse = false;
  s.always_runs = true;  // sees EN fall: the outputs go OFF
  s.handler = [store](ExecContext& c, const BoundOperand* o) { run(*store, c, o); };
  t.add(s);
}

}  // namespace temp
}  // namespace plc_cell
