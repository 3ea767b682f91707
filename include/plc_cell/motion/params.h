#pragma once
// FUN141 MPARA: the 24-register positioning parameter table of one axis (manual §11.6,
// spec §3.8), its validation with the manual's error codes 1-15, and the unit
// conversions (Ut -> pulses, machine speed -> Hz). docs/motion.md has the choices.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace plc_cell {
namespace motion {

constexpr int kParamWords = 24;
constexpr int kParamCount = 18;  // P0..P17
constexpr int64_t kMaxHz = 921600;

// The allowed range of each FUN141 parameter (manual section 11.6, the parameter
// list): the one table behind FUN141's validation, the cell YAML's params: and the ROS
// set_params service. code: the manual's error code (0: the manual gives none, so
// FUN141 accepts any register value there; a service or YAML value outside is still
// refused, since it could not be stored as given).
struct ParamRange {
  int n;
  int code;
  int64_t lo, hi;                  // P0 = 1 or 2 (motor, compound)
  int64_t machine_lo, machine_hi;  // P0 = 0 (machine units)
};
const ParamRange& param_range(int n);  // n in 0..17

// The first bad parameter: its number, the manual's code, the value given and a message
// such as "P9: 7 out of range 0..3".
struct ParamError {
  int n = -1;
  int code = 0;
  int64_t value = 0;
  std::string message;
};
// Pn = v as given (machine: P0 = 0); false with *e filled when out of range.
bool check_param(int n, int64_t v, bool machine, ParamError* e);
// "p8" or "P8" -> 8; -1 for any other key (p18, p08, x).
int param_number(const std::string& key);
// A request for some parameters (ROS set_params): no names and the 18 values P0..P17 in
// order, or each name with its value. False with *why for a name that is no parameter
// or given twice, or counts that do not match.
bool param_changes(const std::vector<std::string>& names, const std::vector<int64_t>& values,
                   std::vector<std::pair<int, int64_t>>* out, std::string* why);

struct AxisParams {
  int p0_unit = 1;            // 0 machine, 1 motor (pulses), 2 compound
  uint32_t p1_ppr = 2000;     // pulses per revolution (A), unsigned 16-bit
  int32_t p2_per_rev = 2000;  // movement per revolution (B): um, mDeg or 0.1 mInch
  int p3_res = 2;             // stroke resolution 0-3
  int32_t p4_max = 460000;    // limited speed (Hz, or cm/min etc. when P0 = 0)
  int32_t p5_start = 141;     // start/stop speed
  int32_t p6_creep = 1000;    // homing creep speed
  int32_t p7_backlash = 0;    // pulses added to every backward move
  int32_t p8_acc_ms = 5000;   // time from 0 to P4 (slope P4/P8)
  int p9_rot = 0;             // P9-0: 1 = position decreases on forward pulses
  int p9_home = 1;            // P9-1: homing toward 0 increasing, 1 decreasing position
  int32_t p10_fwd_comp = 0;   // pulses added to forward moves
  int32_t p11_bwd_comp = 0;   // pulses added to backward moves
  int32_t p12_dec_ms = 0;     // deceleration time from P4 to 0; 0 = P8
  int32_t p13_interp_ms = 500;
  int32_t p14_ppr = 0;        // 32-bit pulses per revolution, overrides P1 when != 0
  uint32_t p15_io = 0xFFFFFFFFu;  // DOG / limit / PG0 / CLR bytes
  int32_t p16_zero = 0;       // position loaded at the end of homing
  int p17_pg0 = 1;            // PG0 pulses to count (DRVZ MD2)

  // Registers SR+0..SR+23, layout of the manual (32-bit values low word first).
  static AxisParams from_registers(const uint16_t* r);
  void to_registers(uint16_t* r) const;
  // Sets Pn (0..17) from one value, P9 as (home << 8) | rot; the YAML `params:` keys and
  // the ROS set_params service both write through it. Returns false for n outside 0..17.
  bool set(int n, int64_t v);

  int64_t get(int n) const;  // Pn as set() takes it

  // 0 if valid, else the manual's code: 1 + parameter number (P0 -> 1 ... P14 -> 15);
  // *e (if given) names the parameter, its range and the value.
  int validate(ParamError* e = nullptr) const;
  // All 18 values as given (before set() narrows them): every parameter against its
  // range, then validate(). False with *e for the first bad one.
  static bool check_values(const int64_t* v, ParamError* e);
  // These parameters with some changed ((n, value as set() takes it), each n once): every
  // value given against its range (machine units when the resulting P0 is 0), then the
  // whole table. False with *e for the first bad one, and *out unchanged.
  bool updated(const std::vector<std::pair<int, int64_t>>& changes, AxisParams* out, ParamError* e) const;

  uint32_t ppr() const { return p14_ppr != 0 ? static_cast<uint32_t>(p14_ppr) : p1_ppr; }
  // Stroke in Ut -> pulses. P0 = 1: Ut is one pulse (AMBIG-20). P0 = 0/2:
  // pulses = stroke * 10^(3 - P3) * A / B, rounded to the nearest pulse.
  int64_t ut_to_pulses(int64_t stroke) const;
  // Pulses -> Ut (FUN143 PSCNV), rounded to the nearest unit.
  int64_t pulses_to_ut(int64_t pulses) const;
  // A speed parameter or SPD value -> Hz: P0 = 0: f = V * 1000 * A / (6 * B); else V.
  double speed_hz(int64_t v) const;
  double max_hz() const { return speed_hz(p4_max); }
  double start_hz() const { return speed_hz(p5_start); }
  double creep_hz() const { return speed_hz(p6_creep); }
  double acc_hz_per_s() const;  // P4/P8 in Hz/s; infinite when P8 = 0
  double dec_hz_per_s() const;  // P4/P12 (P12 = 0: P4/P8)

  int dog_input() const { return byte_in(0); }    // X number or -1
  bool dog_nc() const { return (p15_io & 0x80u) != 0; }
  int limit_input() const { return byte_in(1); }
  bool limit_nc() const { return (p15_io & 0x8000u) != 0; }
  int pg0_input() const { return byte_in(2); }
  bool pg0_rear() const { return (p15_io & 0x800000u) != 0; }
  int clr_output() const { return (p15_io >> 24) == 0xFF ? -1 : static_cast<int>(p15_io >> 24); }

 private:
  int byte_in(int b) const {
    const uint32_t v = (p15_io >> (8 * b)) & 0xFF;
    return v == 0xFF ? -1 : static_cast<int>(v & 0x7F);
  }
};

}  // namespace motion
}  // namespace plc_cell
