#include "plc_cell/temp/sensor_signal.h"

#include <cmath>
#include <cstdlib>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace temp {

const char* unit_name(Unit u) {
  switch (u) {
    case Unit::Celsius: return "C";
    case Unit::Millivolt: return "mV";
    case Unit::Ohm: return "ohm";
    case Unit::Volt: return "V";
    case Unit::Milliamp: return "mA";
  }
  return "?";
}

Quantity parse_quantity(const std::string& text) {
  const char* s = text.c_str();
  char* end = nullptr;
  const double v = std::strtod(s, &end);
  if (end == s || !std::isfinite(v))
    throw Error("'" + text + "' is not a number with a unit (e.g. 4.096 mV, 138.5 ohm, 12 mA, 5 V, 100 C)");
  std::string unit(end);
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  while (!unit.empty() && unit.back() == ' ') unit.pop_back();
  Quantity q;
  q.value = v;
  if (unit == "C" || unit == "degC" || unit == "\u00b0C") q.unit = Unit::Celsius;
  else if (unit == "mV") q.unit = Unit::Millivolt;
  else if (unit == "ohm" || unit == "\u03a9") q.unit = Unit::Ohm;
  else if (unit == "kohm" || unit == "k\u03a9") q.unit = Unit::Ohm, q.value = v * 1000;
  else if (unit == "V") q.unit = Unit::Volt;
  else if (unit == "mA") q.unit = Unit::Milliamp;
  else if (unit.empty()) throw Error("'" + text + "' has no unit (C, mV, ohm, kohm, V or mA)");
  else throw Error("'" + text + "': unknown unit '" + unit + "' (C, mV, ohm, kohm, V or mA)");
  return q;
}

}  // namespace temp
}  // namespace plc_cell
