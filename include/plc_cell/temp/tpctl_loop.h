#pragma once
// The loop machinery FUN86 (FBs and FB versions) and FUN73 share: R4005 latched at EN
// rising, default gains on the first execution, a TpctlPoint solve every Ts, the PWM
// outputs, the R4012/R4013 enables, in-zone bits and the high-temperature /
// heater-open warnings. The instructions differ only in where the PVs come from and
// in their units (TpctlUnits).
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/temp/tpctl.h"

namespace plc_cell {

class ExecContext;

namespace temp {

struct TpctlUnits {
  double full_scale;                       // output range 0..full_scale
  uint64_t (*interval_us)(unsigned code);  // an R4005 byte -> the period
  int gain_max;                            // Kc 1..gain_max, Ki and Td 0..gain_max
  uint16_t kc0, ki0, td0;                  // defaults, into registers left at 0
  uint16_t large_time_min_s;               // R4007's lower limit
  int32_t zone_per_degree = 1;             // readings per degree of R4008 (10: an RTD's 0.1 degC)
};

// One point this scan: the PID works on pid_sv/pid_pv; the in-zone and R4008 checks
// compare zone_pv with Sv +- Os.
struct TpctlPv {
  int32_t pid_sv, pid_pv, zone_pv;
};

struct TpctlLoopState {
  bool active = false;  // EN was on at the previous execution
  uint64_t last_us = 0;
  uint64_t ts_us = 0, cycle_us = 0;
  int ts_tenths = 40;
  uint64_t next_solve = 0, cycle_start = 0;
  std::vector<TpctlPoint> points;
  std::vector<double> duty;  // latched at each PWM cycle start
  std::vector<uint8_t> high_count;
  std::vector<uint64_t> large_since;
  std::vector<TpctlPv> pv;  // the caller fills it each scan (n entries)
};

struct TpctlTables {
  const BoundOperand &yn, &sv, &os, &pr, &ir, &dr, &out;
};

struct TpctlResult {
  uint32_t in_zone = 0, warn = 0;  // bit i = point i of this instruction
  bool alarm = false;
};

// The operand rules every loop instruction shares (FUN73, the FBs and FB FUN86): its
// outputs (operand yn) and its six tables Sv, Os, PR, IR, DR, OR (operands tables ..
// tables + 5) take `count` (the operand zn, when 1 <= zn <= zn_max) points each.
OperandRule tpctl_outputs_rule(size_t yn, size_t zn, int64_t zn_max, const std::string& zn_name);
OperandRule tpctl_tables_rule(size_t tables, size_t zn, int64_t zn_max, const std::string& zn_name);

// EN off, an error, or PVs not ready: the n outputs OFF; with restart the next
// execution starts afresh (takes R4005 again).
void tpctl_outputs_off(TpctlLoopState& st, const BoundOperand& yn, uint32_t n, bool restart);

// One execution with EN on and st.pv filled for n points; first_point is the number
// of point 0 in the R4012/R4013 enable bits. method as TpctlPoint::solve.
TpctlResult tpctl_step(TpctlLoopState& st, ExecContext& c, const TpctlUnits& u, const TpctlTables& t,
                       uint32_t first_point, uint32_t n, bool heating, int method);

}  // namespace temp
}  // namespace plc_cell
