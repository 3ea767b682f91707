#pragma once
// A soft PLC with the motion unit on a virtual clock; every step completion is
// logged with its exact instant.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/interpolation.h"
#include "plc_cell/motion/lin_table.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/motion/params.h"
#include "plc_cell/motion/table.h"

namespace plc_cell {
namespace motion {

// The manual's positioning program example 1 (section 11.6), used by several tests.
inline const char* const kExample1 = R"(; manual 11.6 positioning program example 1
001 SPD 5000
    DRV ADR,+,10000,Ut
    WAIT Time,100
    GOTO NEXT
002 SPD R1000
    DRV ADR+,D100,Ut
    WAIT Time,R500
    GOTO NEXT
003 SPD R1002
    DRV ADR-,D102,Ut
    EXT X0
    GOTO NEXT
004 SPD 2000
    DRV ADR,-,R4072,Ps
    WAIT X1
    GOTO 1
MEND
)";

// The manual's FUN147 example (section 11.6, MHSP0), used by the table and run tests.
inline const char* const kExampleC = R"(; manual FUN147 positioning program with linear interpolation
001 SPD 5000
    LIN ADR,500,400,300,200,Ut
    WAIT TIME,100
    GOTO NEXT
002 SPD R1000
    LIN ADR,D100,D200, , ,Ut
    WAIT TIME,R500
    GOTO NEXT
003 SPD R1002
    LIN ADR,0,0,R300,R400,Ps
    WAIT X0
    GOTO 1
MEND
)";

// FUN141 at R2000 for all four axes (the manual's advice for interpolation), a FUN147
// of group 0 with its table at R0 and WR at R100; M1 = EN, M2 = PAU, M3 = ABT;
// ACT/ERR/DN on M10/M11/M12.
constexpr const char* kGroup0Program = R"(ORG M1925
MPARA Ps=0 SR=R2000 ERR=M13
ORG M1925
MPARA Ps=1 SR=R2000 ERR=M14
ORG M1925
MPARA Ps=2 SR=R2000 ERR=M15
ORG M1925
MPARA Ps=3 SR=R2000 ERR=M16
ORG M1
LD M2
LD M3
MHSP0 Gp=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
END
)";

struct StepDone {
  int ps, step;
  uint64_t t_ns;
};

// FUN141 at R2000 (axis 0), the table at R0, working registers R100; M1 = EN,
// M2 = PAU, M3 = ABT; ACT/ERR/DN on M10/M11/M12.
constexpr const char* kAxis0Program = R"(ORG M1925
MPARA Ps=0 SR=R2000 ERR=M13
ORG M1
LD M2
LD M3
HSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12
END
)";

class MotionCell {
 public:
  // with_counters: the HSC unit too (as SoftCell makes it). isrs records every routine entry.
  explicit MotionCell(const std::string& il = kAxis0Program, bool with_counters = false,
                      hsc::HscConfig counters_cfg = {}) {
    if (with_counters) counters = std::make_unique<hsc::HscUnit>(plc, std::move(counters_cfg));
    unit = std::make_unique<MotionUnit>(plc);
    plc.locked([this](ScanEngine& e, Memory&) {
      timeline::Scheduler::of(e).on_isr([this](uint64_t t, int s) { isrs.push_back({t, s}); });
      return 0;
    });
    unit->on_step_done([this](int ps, int step, uint64_t t) { done.push_back({ps, step, t}); });
    plc.load_program_text(il, "test.il");
    EXPECT_TRUE(plc.set_mode(RunMode::Run));
  }
  void params(const AxisParams& p, uint32_t sr = 2000) {
    uint16_t r[kParamWords];
    p.to_registers(r);
    for (int i = 0; i < kParamWords; ++i) put("R" + std::to_string(sr + i), r[i]);
  }
  // A table's register image at R<sr>, from the text form (FUN140 or FUN147).
  void table(const std::string& text, uint32_t sr = 0) { image<Table>(text, sr, parse_table, encode_table); }
  void lin_table(const std::string& text, uint32_t sr = 0) {
    image<LinTable>(text, sr, parse_lin_table, encode_lin_table);
  }
  template <typename T, typename Parse, typename Encode>
  void image(const std::string& text, uint32_t sr, Parse parse, Encode encode) {
    T t;
    TableError e;
    ASSERT_TRUE(parse(text, &t, &e)) << e.line << ": " << e.message;
    const auto r = encode(t);
    for (size_t i = 0; i < r.size(); ++i) put("R" + std::to_string(sr + i), r[i]);
  }
  void run(uint64_t duration_us, uint64_t period_us = 1000) {
    const uint64_t end = now_us + duration_us;
    while (now_us < end) {
      plc.scan(now_us);
      now_us += period_us;
    }
  }
  // Scans until cond() holds (at most limit_us of virtual time).
  template <typename F>
  bool run_until(F cond, uint64_t limit_us, uint64_t period_us = 1000) {
    const uint64_t end = now_us + limit_us;
    while (now_us < end) {
      plc.scan(now_us);
      now_us += period_us;
      if (cond()) return true;
    }
    return false;
  }
  uint32_t get(const std::string& a) { return plc.read(parse_address(a), 1).at(0); }
  int32_t get32(const std::string& a) { return static_cast<int32_t>(get(a)); }
  void put(const std::string& a, uint32_t v) { plc.write(parse_address(a), {v}); }
  template <typename F>
  auto with(F&& f) {
    return plc.locked([&](ScanEngine&, Memory&) { return f(*unit); });
  }

  Plc plc{SoftCell::functions()};
  std::unique_ptr<hsc::HscUnit> counters;
  std::unique_ptr<MotionUnit> unit;  // after counters: removed from its loop first
  std::vector<std::pair<uint64_t, int>> isrs;
  std::vector<StepDone> done;
  uint64_t now_us = 0;
};

// Test parameters: P8 = 100 ms (4.6 MHz/s), everything else the manual's default.
inline AxisParams fast_params() {
  AxisParams p;
  p.p8_acc_ms = 100;
  return p;
}

}  // namespace motion
}  // namespace plc_cell
