#pragma once
// How well the real-time scan keeps its period, judged over a recent window rather than
// since start: a cell that overran for a minute an hour ago is healthy now, and one that
// overruns now is not hidden by an hour of good scans. docs/scan-engine.md, "Scan health".
#include <array>
#include <cstdint>
#include <string>

namespace plc_cell {

// The last kWindowUs of scan time, in one-second buckets (fixed memory, O(1) per scan).
class ScanWindow {
 public:
  static constexpr uint64_t kWindowUs = 10'000'000;

  // One real-time scan at now_us (the scan's time): how late it woke, how many periods it
  // then missed.
  void add(uint64_t now_us, uint64_t wake_latency_ns, uint64_t missed_periods);

  struct Summary {
    uint64_t scans = 0;
    uint64_t overruns = 0;  // periods missed
    uint64_t max_wake_latency_ns = 0;
  };
  // The scans of the window that ends at now_us.
  Summary summary(uint64_t now_us) const;

 private:
  struct Bucket {
    uint64_t second = UINT64_MAX;  // now_us / 1 s of its scans; UINT64_MAX: unused
    Summary s;
  };
  std::array<Bucket, kWindowUs / 1'000'000> buckets_{};
};

enum class ScanHealthLevel { Ok, Warn, Error };

struct ScanHealth {
  ScanHealthLevel level = ScanHealthLevel::Ok;
  std::string reason;  // empty when Ok
};

// The thresholds, as fractions of the configured period (docs/scan-engine.md):
// WARN when more than 0.1 % of the window's periods were missed or a wake came later than
// half a period; ERROR when more than 5 % were missed.
constexpr double kOverrunWarnFraction = 0.001;
constexpr double kOverrunErrorFraction = 0.05;
constexpr double kLatencyWarnFraction = 0.5;

ScanHealth assess_scan(const ScanWindow::Summary& window, uint64_t period_us);

}  // namespace plc_cell
