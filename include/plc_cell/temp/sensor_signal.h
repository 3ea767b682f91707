#pragma once
// A sensor's signal in physical units, as the cell YAML writes a channel's `value`:
// "4.096 mV" (thermocouple emf), "138.5055 ohm" or "10 kohm" (RTD, NTC), "12 mA" and
// "5 V" (analog inputs), "100 C". docs/analog-and-temperature.md.
#include <string>

namespace plc_cell {
namespace temp {

enum class Unit { Celsius, Millivolt, Ohm, Volt, Milliamp };

struct Quantity {
  double value = 0;  // in the unit (kohm is stored as ohm)
  Unit unit = Unit::Celsius;
};

// A number, optional spaces, a unit: C (degC, °C), mV, ohm (Ω), kohm (kΩ), V, mA.
// Throws Error naming the text and the units known.
Quantity parse_quantity(const std::string& text);
const char* unit_name(Unit u);

}  // namespace temp
}  // namespace plc_cell
