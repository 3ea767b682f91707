#pragma once
// FUN139 HSPWM, the high-speed PWM of the FBs transistor outputs Y0, Y2, Y4, Y6 (the
// operands as the PWMDA appendix gives them, manual A:530-A:545). The pulse train is
// far faster than a scan, so it is kept as a duty and a frequency per output, which
// the PWMDA model (pwmda.h) turns into a voltage. docs/analog-and-temperature.md.
#include <cstdint>

namespace plc_cell {
class FunctionTable;
class ScanEngine;
namespace temp {

constexpr int kHsPwmOutputs = 4;  // Pw 0..3 = Y0, Y2, Y4, Y6

struct HsPwmChannel {
  bool running = false;  // EN on
  double duty = 0;       // fraction of the period the output is ON, after Op
  double frequency_hz = 0;
};

// f = 18.432 MHz / ((Pn + 1) x steps), steps = 1000 (Rs 1) or 100 (Rs 0): Pn 1 at
// 1/1000 gives the manual's 9.2 kHz (plc_cell's derivation; the instruction chapter
// that defines Pn is not in the sources).
double hspwm_frequency_hz(int pn, int rs);

// The generator state of the PLC of engine for output Pw (zeroed if FUN139 never ran).
HsPwmChannel hspwm_channel(const ScanEngine& engine, int pw);
// Switches the PLC's generators off (STOP).
void hspwm_reset(ScanEngine& engine);

void add_hspwm_function(FunctionTable& t);

}  // namespace temp
}  // namespace plc_cell
