#pragma once
// FBs analog I/O codes (manual A:5885-A:6410): signal <-> 14-bit code, the 12-bit and
// "14-bit format, valid 12-bit" forms, and the 4-20 mA offset value. Pure math.
#include <cstdint>
#include <string>

namespace plc_cell {
namespace temp {

// One of the 8 jumper combinations: polarity and span common to a module, V or I per channel.
struct AnalogRange {
  bool bipolar_signal = true;  // JP3
  bool span10 = true;          // JP2: 10 V / 20 mA, else 5 V / 10 mA
  bool current = false;        // per channel: mA instead of V
  double lo() const { return bipolar_signal ? -hi() : 0.0; }
  double hi() const { return (span10 ? 10.0 : 5.0) * (current ? 2.0 : 1.0); }
};

// Signal -> 14-bit code: the range ends map to the code ends (0..16383 unipolar code,
// -8192..8191 bipolar code = unipolar - 8192), saturating beyond them. Rounded to the
// nearest count, except that mid-scale of a bipolar signal reads exactly 8192 / 0 as
// the manual's example says (the formula gives 8191.5).
int32_t ai_code14(const AnalogRange& r, double signal, bool bipolar_code);
// As the IR holds it: 14-bit, or 14-bit format with valid 12 bits (B1 = B0 = 0),
// or the 12-bit format (the 14-bit value / 4).
enum class AiFormat { Valid14, Valid12In14, Bits12 };
int32_t ai_register(int32_t code14, AiFormat f);

// Code in an OR -> output signal, the code clamped to its range first.
double ao_signal(const AnalogRange& r, int32_t code, bool bipolar_code);

// The manual's 4-20 mA offset value on a 0-20 mA input (A:6185): IR (+ 8192 for a
// bipolar code) - 3276, negative -> 0, x 20/16, clamped to 16383.
int32_t offset_4_20(int32_t ir, bool bipolar_code);

}  // namespace temp
}  // namespace plc_cell
