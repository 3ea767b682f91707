#include "plc_cell/core/scan_health.h"

#include <cstdio>

namespace plc_cell {

void ScanWindow::add(uint64_t now_us, uint64_t wake_latency_ns, uint64_t missed_periods) {
  const uint64_t second = now_us / 1'000'000;
  Bucket& b = buckets_[second % buckets_.size()];
  if (b.second != second) b = Bucket{second, {}};  // a second that left the window
  ++b.s.scans;
  b.s.overruns += missed_periods;
  if (wake_latency_ns > b.s.max_wake_latency_ns) b.s.max_wake_latency_ns = wake_latency_ns;
}

ScanWindow::Summary ScanWindow::summary(uint64_t now_us) const {
  const uint64_t second = now_us / 1'000'000;
  Summary out;
  for (const Bucket& b : buckets_) {
    if (b.second == UINT64_MAX || b.second > second || second - b.second >= buckets_.size()) continue;
    out.scans += b.s.scans;
    out.overruns += b.s.overruns;
    if (b.s.max_wake_latency_ns > out.max_wake_latency_ns) out.max_wake_latency_ns = b.s.max_wake_latency_ns;
  }
  return out;
}

ScanHealth assess_scan(const ScanWindow::Summary& w, uint64_t period_us) {
  ScanHealth h;
  const uint64_t periods = w.scans + w.overruns;  // each scan had its period, each miss one
  char text[200];
  if (periods > 0 && w.overruns > 0) {
    const double fraction = double(w.overruns) / double(periods);
    if (fraction > kOverrunWarnFraction) {
      h.level = fraction > kOverrunErrorFraction ? ScanHealthLevel::Error : ScanHealthLevel::Warn;
      // The thresholds are on the docs page, not in the text: a monitor that greps the
      // status for "error" must not see one in a mere warning.
      std::snprintf(text, sizeof text, "%llu of the last %llu periods overrun (%.2f %%)",
                    static_cast<unsigned long long>(w.overruns), static_cast<unsigned long long>(periods),
                    fraction * 100);
      h.reason = text;
    }
  }
  if (double(w.max_wake_latency_ns) > kLatencyWarnFraction * double(period_us) * 1000) {
    if (h.level == ScanHealthLevel::Ok) h.level = ScanHealthLevel::Warn;
    std::snprintf(text, sizeof text, "woke up to %llu us late, over half the %llu us period",
                  static_cast<unsigned long long>(w.max_wake_latency_ns / 1000), static_cast<unsigned long long>(period_us));
    h.reason += (h.reason.empty() ? "" : "; ") + std::string(text);
  }
  return h;
}

}  // namespace plc_cell
