#pragma once
// Thermocouples J, K, E, T, R, S, B, N by the NIST ITS-90 reference functions
// (NIST Monograph 175): EMF from temperature and the approximate inverse functions.
// Pure math, no PLC state.
#include <string>

namespace plc_cell {
namespace temp {

enum class TcType { J, K, E, T, R, S, B, N };

// "J", "k", ... -> type; throws Error on an unknown letter.
TcType tc_type_from_string(const std::string& s);
const char* to_string(TcType t);

// Range of the NIST reference function in degC (where emf() is defined).
double tc_min_c(TcType t);
double tc_max_c(TcType t);

// Thermoelectric EMF in mV of a junction at t_c against a 0 degC reference.
// Outside the reference range the end polynomial is extrapolated.
double tc_emf_mv(TcType t, double t_c);

// Temperature (degC) for an EMF in mV against 0 degC, by the NIST inverse polynomial
// of the sub-range (its error is at most 0.06 degC). Clamped to the inverse's
// sub-ranges at the ends, so beyond them the value is extrapolated.
double tc_temp_c(TcType t, double emf_mv);

// What a module with cold-junction compensation reads: the terminals see
// emf(hot) - emf(cold); the module adds emf(cold) back and inverts.
double tc_measured_emf_mv(TcType t, double hot_c, double cold_junction_c);
double tc_compensated_c(TcType t, double terminal_emf_mv, double cold_junction_c);

}  // namespace temp
}  // namespace plc_cell
