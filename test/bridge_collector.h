#pragma once
// Test helper for the bridges' bus sides (fatek::Bridge, tri::Bridge): everything a bridge
// reports through its sinks, and bounded waits on it (never sleeps).
#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/io/polled_link.h"

namespace bridge_test {

class Collector {
 public:
  // Sinks: a bridge's Sinks struct (io, group, error).
  template <class Sinks>
  Sinks sinks() {
    Sinks s;
    s.io = [this](const plc_cell::IoResult& r) { add([&] { io.push_back(r); }); };
    s.group = [this](const plc_cell::GroupResult& r) { add([&] { groups.push_back(r); }); };
    s.error = [this](const std::string& e) { add([&] { errors.push_back(e); }); };
    return s;
  }
  // Until pred (called with the lock held) holds after a report, at most timeout_s.
  bool wait(const std::function<bool()>& pred, int timeout_s = 10) {
    std::unique_lock<std::mutex> lk(mu_);
    return cv_.wait_for(lk, std::chrono::seconds(timeout_s), pred);
  }
  // Reports from now on only.
  void clear() {
    std::lock_guard<std::mutex> lk(mu_);
    io.clear();
    groups.clear();
    errors.clear();
  }
  std::vector<plc_cell::IoResult> io;
  std::vector<plc_cell::GroupResult> groups;
  std::vector<std::string> errors;

 private:
  void add(const std::function<void()>& f) {
    {
      std::lock_guard<std::mutex> lk(mu_);
      f();
    }
    cv_.notify_all();
  }
  std::mutex mu_;
  std::condition_variable cv_;
};

// A bridge's config (fatek::BridgeConfig, tri::BridgeConfig) on a loopback TCP port, polling
// fast, failing fast and reconnecting at once.
template <class Cfg>
Cfg loopback_link(int port, Cfg cfg) {
  cfg.tcp = "127.0.0.1:" + std::to_string(port);
  cfg.timeout_s = 1.0;
  cfg.retries = 0;
  cfg.io_rate_hz = 100;
  cfg.backoff_min_s = 0.01;
  cfg.backoff_max_s = 0.05;
  return cfg;
}

}  // namespace bridge_test
