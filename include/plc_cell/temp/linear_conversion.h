#pragma once
// FUN33 linear conversion and FUN32 4-20 mA offset conversion (the manual's 4-20 mA
// examples, A:6185-A:6212 and A:6363-A:6390). docs/analog-and-temperature.md.
#include <cstdint>

namespace plc_cell {
class FunctionTable;
namespace temp {

// FUN33's table Ts = [Smin, Smax, Dmin, Dmax]: D = Dmin + (S - Smin)(Dmax - Dmin)/(Smax - Smin),
// rounded half away from zero, not clamped to [Dmin, Dmax] (the manual's input example
// gives -4094 for S = 0), saturated to 16 bits. Smax = Smin gives Dmin.
int32_t linear_convert(int32_t s, int32_t smin, int32_t smax, int32_t dmin, int32_t dmax);

// FUN32 ADCNV (plc_cell's operands): Md 0 unipolar / 1 bipolar code, N registers from S
// through offset_4_20() into D. FUN33 LCNV: N registers from S through Ts into D.
void add_linear_conversion_functions(FunctionTable& t);

}  // namespace temp
}  // namespace plc_cell
