#pragma once
// The measuring half of FUN72 TP4, FUN73 TSTC and FUN85 TPSNS (FB generation, second
// source B:323-B:922): drives a module's multiplexing DO one point at a time, reads its
// temperature AI(s) after the R4014 / R4004 ms per point, and turns the AI into the
// primitive (R3968 + point), the engineering value (TR / SR) and the line-broken bits.
#include <cstdint>
#include <vector>

#include "plc_cell/core/function_table.h"

namespace plc_cell {

class ExecContext;

namespace temp {

enum FbTp { kFbK = 0, kFbJ = 1, kFbPt100 = 2, kFbPt1000 = 3 };

struct FbPoints {
  int tp = 0, pl = 0;
  bool fun85 = false;       // R4000-R4004 (FUN85) instead of R4014-R4019 (FUN72/73)
  uint32_t first_point = 0; // Sm (FUN72/73) or 0: primitives at R3968 + first_point + i
  int points = 4;           // 4 or Zn
  int per_ai = 4;           // points multiplexed on one AI: 4 (FB-2A?4) or 6 (FB-4AJ(K)xx)
  uint32_t ai[4] = {};      // R3840 + ai[g]: the AI of group g
};

struct FbMeasureState {
  bool running = false;
  int step = 0;             // the point (of each group) selected now
  uint64_t t_select = 0;    // when it was selected
  uint64_t last_us = 0;
  uint32_t measured = 0;    // points converted at least once
  uint16_t cycles = 0;      // completed multiplex cycles
  std::vector<std::vector<int32_t>> window;  // per point: the last samples (averaging)
};

// FUN85's R4000 signature and defaults: when R4000's low byte is not this Tp/Pl's
// signature, R4000-R4004 get their defaults (B:878-B:913).
void fb_fun85_init(ExecContext& c, int tp, int pl);

// The slot (ms per point) and the positive factor the instruction uses now.
uint32_t fb_slot_ms(const ExecContext& c, const FbPoints& p);
double fb_pos_factor(const ExecContext& c, const FbPoints& p);

// A TC set point (degC) in primitive counts with factor pos: the PID's units.
int32_t fb_counts_of(int32_t degc, int pl, double pos);
// An RTD's reading or set point (0.1 degC) in primitive counts: 0..4095 over the span's
// range of the curve R4020's high byte names (R3968 + n of an RTD point).
int32_t fb_rtd_counts_of(const ExecContext& c, int32_t tenths, int pl);

// One execution with EN on: tr gets one word per point, wr[0] (and wr[1] for points
// 16-23) the line-broken bits. Returns true while any point is line-broken (ALM).
bool fb_measure_step(FbMeasureState& st, ExecContext& c, const FbPoints& p, const BoundOperand& ym, uint16_t* tr,
                     uint16_t* wr);
// EN off: the DO off; the next EN starts the cycle from point 0.
void fb_measure_stop(FbMeasureState& st, const FbPoints& p, const BoundOperand& ym);
inline bool fb_all_measured(const FbMeasureState& st, const FbPoints& p) {
  return st.measured == (p.points >= 32 ? 0xFFFFFFFFu : (1u << p.points) - 1);
}

}  // namespace temp
}  // namespace plc_cell
