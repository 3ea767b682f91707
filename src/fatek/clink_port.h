#pragma once
// FUN151's side of one COM port (src/fatek/clink.cpp builds the ports, clink_function.cpp
// is the instruction): shared by the two files, not part of the interface.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>

#include "plc_cell/fatek/clink.h"

namespace plc_cell {
namespace fatek {

// FUN151's use of one COM port: one transaction at a time, run on the port's thread
// (shared with FUN150 on the same port). A job is a FATEK request (MD0) or raw bytes out
// and/or a raw message in (MD1/MD2).
struct ClinkPorts::Port {
  struct Raw {
    std::string tx;
    bool rx = false;
    uint8_t start = 0, end = 0;  // 0 = none (a quiet gap ends the message)
    int gap_ms = 12;
    int timeout_ms = 500;        // <= 0: wait until a message arrives or the job is cancelled
  };
  std::shared_ptr<ComPort> com;
  std::unique_ptr<Client> client;
  int timeout_ms = 500;
  std::mutex mu;
  std::condition_variable cv;
  bool has_job = false, done = false, stop = false;
  std::atomic<bool> cancel{false};
  bool raw_job = false;
  Request job;
  Raw raw;
  Response rsp;
  std::string received;
  ClinkResult result = ClinkResult::Ok;

  ClinkResult run_raw(const Raw& r, std::string* in) {
    Transport& t = client->transport();
    if (!r.tx.empty()) t.send(r.tx, timeout_ms);
    if (!r.rx) return ClinkResult::Ok;
    const auto t0 = std::chrono::steady_clock::now();
    auto last = t0;
    bool started = r.start == 0;
    char buf[256];
    for (;;) {
      if (cancel) return ClinkResult::Timeout;
      const auto now = std::chrono::steady_clock::now();
      const auto ms = [](auto d) { return std::chrono::duration_cast<std::chrono::milliseconds>(d).count(); };
      if (!in->empty() && r.end == 0 && ms(now - last) >= r.gap_ms) return ClinkResult::Ok;
      if (in->empty() && r.timeout_ms > 0 && ms(now - t0) >= r.timeout_ms) return ClinkResult::Timeout;
      const int wait = in->empty() || r.end != 0 ? 20 : std::max(1, r.gap_ms - int(ms(now - last)));
      const size_t n = t.recv(buf, sizeof buf, wait);
      if (n) last = std::chrono::steady_clock::now();
      for (size_t i = 0; i < n; ++i) {
        const uint8_t b = uint8_t(buf[i]);
        if (!started) {
          if (b != r.start) continue;  // bytes before the start code are dropped
          started = true;
        }
        in->push_back(char(b));
        if (in->size() > 511) return ClinkResult::BadData;
        if (r.end != 0 && b == r.end) return ClinkResult::Ok;
      }
    }
  }

  // The instruction set has_job under mu: hand the transaction to the port's thread.
  void post() {
    com->submit([this] { run_one(); });
  }

  void run_one() {
    std::unique_lock<std::mutex> lk(mu);
    if (stop) {
      has_job = false;
      cv.notify_all();
      return;
    }
    const bool is_raw = raw_job;
    Request req = job;
    Raw r = raw;
    lk.unlock();
    Response out;
    std::string in;
    ClinkResult res = ClinkResult::Ok;
    try {
      if (is_raw) res = run_raw(r, &in);
      else out = client->transact(req);
    } catch (const PlcError&) {
      res = ClinkResult::BadData;  // the slave answered with an error code
    } catch (const CommError& e) {
      res = std::string(e.what()).find("no answer") != std::string::npos ? ClinkResult::Timeout : ClinkResult::BadData;
    } catch (const std::exception&) {
      res = ClinkResult::BadData;
    }
    lk.lock();
    rsp = std::move(out);
    received = std::move(in);
    result = res;
    has_job = false;
    done = true;
    cv.notify_all();
  }
};

}  // namespace fatek
}  // namespace plc_cell
