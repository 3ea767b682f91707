#pragma once
// The PLC's lock, for one holder that works in steps (a virtual-time run: scan after scan,
// back to back) and clients that come at any time (host links, services, the monitor).
//
// Taking and giving back a mutex at every scan is two atomic read-modify-writes and two
// calls into libc: a sixth of the cost of an idle cell's scan in `plc_cell sim`. So the
// stepping holder keeps the lock across steps and, between two steps, lets the clients
// in only when one waits. It then waits until at least one of them has had the lock
// before it takes it again: a plain unlock and lock would win the race against a client
// just woken by the kernel, scan after scan, and starve it. A client thus waits at most
// one step, as it did when the lock was taken per scan.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <thread>

namespace plc_cell {

class HandoffMutex {
 public:
  // BasicLockable, for std::lock_guard and std::unique_lock.
  void lock() {
    arrivals_.fetch_add(1);
    mu_.lock();
    admitted_.fetch_add(1);
  }
  void unlock() { mu_.unlock(); }

  // Called by the holder between two steps: lets in the clients that wait, if any, and
  // returns holding the lock again. Two loads when nobody waits.
  void let_waiters_in() {
    const uint64_t admitted = admitted_.load(std::memory_order_relaxed);
    if (arrivals_.load(std::memory_order_relaxed) == admitted) return;
    mu_.unlock();
    // One of them takes the free mutex (it is blocked on it, or about to try); this
    // thread's own acquisition below counts neither as an arrival nor as an admission.
    while (admitted_.load(std::memory_order_acquire) == admitted) std::this_thread::yield();
    mu_.lock();
  }

  // Clients counted in lock() that do not yet hold the lock (tests, diagnostics). The
  // admissions are read first: arrivals only grow, so the difference is never negative.
  uint64_t waiting() const {
    const uint64_t admitted = admitted_.load();
    return arrivals_.load() - admitted;
  }

 private:
  std::mutex mu_;
  std::atomic<uint64_t> arrivals_{0};  // lock() calls begun
  std::atomic<uint64_t> admitted_{0};  // ... that hold or have held the lock
};

}  // namespace plc_cell
