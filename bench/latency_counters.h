#pragma once
// Request latencies of a protocol benchmark as Google Benchmark counters: p50, p99 and the
// request rate, so every protocol's figures read the same way side by side.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <vector>

inline void latency_counters(benchmark::State& st, std::vector<double>& us) {
  if (us.empty()) return;
  std::sort(us.begin(), us.end());
  st.counters["p50_us"] = us[us.size() / 2];
  st.counters["p99_us"] = us[std::min(us.size() - 1, us.size() * 99 / 100)];
  st.counters["req_per_s"] = benchmark::Counter(double(us.size()), benchmark::Counter::kIsRate);
}
