#include "plc_cell/temp/loop_settings.h"

#include <cmath>
#include <cstdio>

namespace plc_cell {
namespace temp {
namespace {

// 4000 -> "4000.0", 3276.75 -> "3276.75": the value as given, at least to 0.1.
std::string degrees(double v) {
  char b[64];
  if (std::isfinite(v) && std::fabs(v * 10 - std::round(v * 10)) < 1e-9 && std::fabs(v) < 1e15)
    std::snprintf(b, sizeof b, "%.1f", v);
  else
    std::snprintf(b, sizeof b, "%.10g", v);
  return b;
}

std::string gain(const char* name, int32_t v, bool has, int32_t lo, const LoopDef& loop) {
  if (v == -1) return "";
  if (!has)
    return std::string(name) + " " + std::to_string(v) + ": loop '" + loop.name + "' has no " + name +
           " register (give " + name + ": in its modules.temperature.loops entry)";
  if (v < lo || v > kGainMax)
    return std::string(name) + " " + std::to_string(v) + " out of range " + std::to_string(lo) + ".." +
           std::to_string(kGainMax) + " (-1 leaves it unchanged)";
  return "";
}

}  // namespace

std::string check_loop_change(const LoopDef& loop, const LoopChange& c, bool fahrenheit) {
  if (!std::isnan(c.setpoint)) {
    const double tenths = std::round(c.setpoint * 10);
    if (!(tenths >= -32768 && tenths <= 32767))
      return "setpoint " + degrees(c.setpoint) + (fahrenheit ? " \u00b0F" : " \u00b0C") + " out of range " +
             degrees(kSetpointMin) + ".." + degrees(kSetpointMax) + " (NaN leaves it unchanged)";
  }
  for (const std::string& e : {gain("kc", c.kc, loop.has_kc, 1, loop), gain("ki", c.ki, loop.has_ki, 0, loop),
                               gain("td", c.td, loop.has_td, 0, loop)})
    if (!e.empty()) return e;
  return "";
}

void apply_loop_change(const LoopDef& loop, const LoopChange& c, Memory& m) {
  if (!std::isnan(c.setpoint)) m.set_reg(loop.sv.area, loop.sv.index, uint16_t(int16_t(std::lround(c.setpoint * 10))));
  if (c.kc != -1) m.set_reg(loop.kc.area, loop.kc.index, uint16_t(c.kc));
  if (c.ki != -1) m.set_reg(loop.ki.area, loop.ki.index, uint16_t(c.ki));
  if (c.td != -1) m.set_reg(loop.td.area, loop.td.index, uint16_t(c.td));
}

}  // namespace temp
}  // namespace plc_cell
