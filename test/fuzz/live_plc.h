#pragma once
// A Plc in RUN with its real-time loop scanning every millisecond, for fuzzers that drive
// the servers' request handlers in place. After each input, check_scan() turns a stall into
// a finding: a scan (lock wait included, as RealTimeLoop measures it) longer than the
// budget, or any fault (the watchdog's included). Budget: 100 ms, or
// PLC_CELL_FUZZ_SCAN_BUDGET_MS. The Plc and the loop are never destroyed: libFuzzer exits
// from its own thread while the loop runs.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <thread>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/realtime_loop.h"
#include "plc_cell/core/writable_ranges.h"

// ThreadSanitizer builds: libFuzzer clears and reads the coverage counters from its own
// thread while the scan thread (instrumented too) bumps them. Those reports are about the
// fuzzer's bookkeeping, not the PLC; each suppression names a libFuzzer function that only
// appears in such a stack, so a race between a handler and the scan is still reported.
// Not instrumented: TSan calls it while it initialises itself.
extern "C" __attribute__((disable_sanitizer_instrumentation)) const char* __tsan_default_suppressions() {
  return "race:fuzzer::TracePC::ClearInlineCounters\n"
         "race:fuzzer::TracePC::CollectFeatures\n"
         "race:fuzzer::TracePC::UpdateObservedPCs\n";
}

namespace live_plc {

// ThreadSanitizer itself stops every thread now and then for several hundred ms (its
// periodic reset of the shadow state), whoever holds the PLC lock. Under it the targets
// look for races and lock-order errors only: no scan budget, no watchdog. The ASan+UBSan
// builds check the budget.
#if defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define LIVE_PLC_TSAN 1
#endif
#endif
#ifdef LIVE_PLC_TSAN
constexpr bool kThreadSanitizer = true;
#else
constexpr bool kThreadSanitizer = false;
#endif

// Clients may write the program's data, not the special registers, the watchdog setting or
// RUN/STOP: the scan must then have no reason to stop, so any fault is a finding.
inline const char* kWritable = "D0-D3999,R0-R2999,M0-M1399,Y0-Y255,S0-S999";

struct Live {
  plc_cell::Plc plc;
  plc_cell::RealTimeLoop loop{plc, std::chrono::milliseconds(1)};
  plc_cell::WritableRanges writable = plc_cell::WritableRanges::parse(kWritable);
  // A scan preempted on a loaded machine under ASan took 68 ms: the budget tells a stall
  // (a sleep under the PLC lock) from that, not from a fast scan.
  uint64_t budget_ns = 100000000;
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
    if (kThreadSanitizer) p->budget_ns = 0;  // reported as "budget 0 ms": not checked
    // D200 counts scans; R0 follows it so the program touches the registers clients write.
    p->plc.load_program_text("ORG M1925\nINC D=D200\nMOV S=D200 D=R0\nEND\n", "live.il");
    p->plc.set_mode(plc_cell::RunMode::Run);
    // Warm-up: the first scans of a sanitizer build pay for mapping shadow memory (several
    // hundred ms under ThreadSanitizer). They run with a lenient watchdog and do not count.
    const uint64_t watchdog = p->plc.locked([](plc_cell::ScanEngine& e, plc_cell::Memory&) {
      const uint64_t w = e.watchdog_us();
      e.set_watchdog_us(60000000);
      return w;
    });
    p->loop.start();
    for (int i = 0; i < 10000; ++i) {  // at most 10 s
      if (p->plc.locked([](plc_cell::ScanEngine& e, plc_cell::Memory&) { return e.stats().scans; }) >= 100) break;
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    p->plc.locked([watchdog](plc_cell::ScanEngine& e, plc_cell::Memory&) {
      if (!kThreadSanitizer) e.set_watchdog_us(watchdog);
      e.reset_stats();
      return 0;
    });
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
  if ((!kThreadSanitizer && r.first > l.budget_ns) || !r.second.empty()) {
    report(l, r.second.empty() ? "scan over budget" : ("fault: " + r.second).c_str());
    std::abort();
  }
}

}  // namespace live_plc
