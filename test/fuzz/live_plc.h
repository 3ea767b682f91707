#pragma once
// A Plc in RUN with its real-time loop scanning every millisecond, for fuzzers that drive
// the servers' request handlers in place. After each input, check_scan() turns a stall into
// a finding: a scan (lock wait included, as RealTimeLoop measures it) longer than the
// budget, or any fault (the watchdog's included). Budget: 50 ms, or
// PLC_CELL_FUZZ_SCAN_BUDGET_MS. The Plc and the loop are never destroyed: libFuzzer exits
// from its own thread while the loop runs.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/core/writable_ranges.h"

namespace live_plc {

// Clients may write the program's data, not the special registers, the watchdog setting or
// RUN/STOP: the scan must then have no reason to stop, so any fault is a finding.
inline const char* kWritable = "D0-D3999,R0-R2999,M0-M1399,Y0-Y255,S0-S999";

struct Live {
  plc_cell::Plc plc;
  plc_cell::RealTimeLoop loop{plc, std::chrono::milliseconds(1)};
  plc_cell::WritableRanges writable = plc_cell::WritableRanges::parse(kWritable);
  uint64_t budget_ns = 50000000;
  uint64_t inputs = 0;
};

inline void report(const Live& l, const char* what) {
  const auto st = l.plc.locked([](const plc_cell::ScanEngine& e, const plc_cell::Memory&) { return e.stats(); });
  std::fprintf(stderr, "scan watch: %s: %llu inputs, %llu scans, longest scan %.3f ms (budget %.0f ms)\n", what,
               (unsigned long long)l.inputs, (unsigned long long)st.scans, st.cycle.max_ns / 1e6, l.budget_ns / 1e6);
}

inline Live& live() {
  static Live* l = [] {
    auto* p = new Live;
    if (const char* b = std::getenv("PLC_CELL_FUZZ_SCAN_BUDGET_MS")) p->budget_ns = uint64_t(std::atof(b) * 1e6);
    // D200 counts scans; R0 follows it so the program touches the registers clients write.
    p->plc.load_program_text("ORG M1925\nINC D=D200\nMOV S=D200 D=R0\nEND\n", "live.il");
    p->plc.set_mode(plc_cell::RunMode::Run);
    p->loop.start();
    std::atexit([] { report(live(), "done"); });
    return p;
  }();
  return *l;
}

inline void check_scan(Live& l) {
  ++l.inputs;
  const auto r = l.plc.locked([](const plc_cell::ScanEngine& e, const plc_cell::Memory&) {
    return std::make_pair(e.stats().cycle.max_ns, e.fault());
  });
  if (r.first > l.budget_ns || !r.second.empty()) {
    report(l, r.second.empty() ? "scan over budget" : ("fault: " + r.second).c_str());
    std::abort();
  }
}

}  // namespace live_plc
