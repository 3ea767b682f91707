#pragma once
// Fault injection on a serial line: two ptys with a proxy thread between them. The server
// opens device_link(), the client client_link() (stable symlinks in a temp folder). Per
// chunk of bytes the proxy may drop one byte, flip one bit, or cut the chunk short (seeded
// RNG), may go silent, and can unplug/replug the device side (its pty disappears, a new
// one comes, the symlink follows) as a USB adapter does, and may hold the device's bytes
// back for a while (a device that answers late, in order).
#include <fcntl.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <mutex>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>

#include "temp_dir.h"

class PtyProxy {
 public:
  struct Faults {
    double drop = 0;     // per chunk: drop one byte
    double corrupt = 0;  // per chunk: flip one bit of one byte
    double cut = 0;      // per chunk: forward only a prefix
    bool silent = false; // forward nothing (a device that stopped answering)
    int delay_ms = 0;    // the device's bytes reach the client this late, in order (a slow device)
  };

  PtyProxy(const std::string& folder, uint32_t seed) : folder_(folder), rng_(seed) {
    if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error("pipe");
    open_pty(&client_master_, &client_hold_, client_link());
    open_pty(&dev_master_, &dev_hold_, device_link());
    thread_ = std::thread([this] { run(); });
  }
  ~PtyProxy() {
    stop_ = true;
    (void)!::write(wake_[1], "x", 1);
    thread_.join();
    if (client_master_ >= 0) ::close(client_master_);
    if (client_hold_ >= 0) ::close(client_hold_);
    if (dev_master_ >= 0) ::close(dev_master_);
    if (dev_hold_ >= 0) ::close(dev_hold_);
    ::close(wake_[0]);
    ::close(wake_[1]);
  }
  std::string device_link() const { return folder_ + "/device"; }
  std::string client_link() const { return folder_ + "/client"; }

  void set_faults(const Faults& f) {
    std::lock_guard<std::mutex> lk(mu_);
    faults_ = f;
  }
  // The device side vanishes: its pty master closes (the server sees a hang-up) and the link goes.
  void unplug() {
    std::lock_guard<std::mutex> lk(mu_);
    ::unlink(device_link().c_str());
    ::close(dev_master_);
    ::close(dev_hold_);
    dev_master_ = dev_hold_ = -1;
    (void)!::write(wake_[1], "x", 1);
  }
  // A new device pty at the same link.
  void replug() {
    std::lock_guard<std::mutex> lk(mu_);
    open_pty(&dev_master_, &dev_hold_, device_link());
    (void)!::write(wake_[1], "x", 1);
  }
  // The same on the client side (a master's own USB adapter pulled and plugged back).
  void unplug_client() {
    std::lock_guard<std::mutex> lk(mu_);
    ::unlink(client_link().c_str());
    ::close(client_master_);
    ::close(client_hold_);
    client_master_ = client_hold_ = -1;
    (void)!::write(wake_[1], "x", 1);
  }
  void replug_client() {
    std::lock_guard<std::mutex> lk(mu_);
    open_pty(&client_master_, &client_hold_, client_link());
    (void)!::write(wake_[1], "x", 1);
  }
  uint64_t faults_injected() const { return injected_; }

 private:
  // Raw from the start (no echo before the user sets its own mode). The proxy keeps a
  // slave fd open so the master never reports a hang-up while nobody else has it open.
  static void open_pty(int* master, int* hold, const std::string& link) {
    char name[256];
    termios raw{};
    ::cfmakeraw(&raw);
    if (::openpty(master, hold, name, &raw, nullptr) != 0) throw std::runtime_error("openpty");
    ::fcntl(*master, F_SETFD, FD_CLOEXEC);
    ::fcntl(*hold, F_SETFD, FD_CLOEXEC);
    ::unlink(link.c_str());
    if (::symlink(name, link.c_str()) != 0) throw std::runtime_error("symlink " + link);
  }

  // The device's bytes held back (delay_ms), with when they are due at the client.
  struct Held {
    std::chrono::steady_clock::time_point due;
    std::string bytes;
  };

  static void write_out(int to, const std::string& s) {
    size_t off = 0;
    while (off < s.size()) {
      const ssize_t w = ::write(to, s.data() + off, s.size() - off);
      if (w <= 0) return;
      off += size_t(w);
    }
  }

  // Held bytes that are due, in order; the ms until the next is (or -1: none held).
  int release_held() {
    const auto now = std::chrono::steady_clock::now();
    while (!held_.empty() && held_.front().due <= now) {
      if (client_master_ >= 0) write_out(client_master_, held_.front().bytes);
      held_.pop_front();
    }
    if (held_.empty()) return -1;
    return int(std::chrono::duration_cast<std::chrono::milliseconds>(held_.front().due - now).count()) + 1;
  }

  void forward(int from, int to) {
    char buf[512];
    const ssize_t n = ::read(from, buf, sizeof buf);
    if (n <= 0 || to < 0) return;
    std::string s(buf, size_t(n));
    std::uniform_real_distribution<double> u(0, 1);
    if (faults_.silent) return;
    if (u(rng_) < faults_.drop) {
      s.erase(std::uniform_int_distribution<size_t>(0, s.size() - 1)(rng_), 1);
      ++injected_;
    }
    if (!s.empty() && u(rng_) < faults_.corrupt) {
      s[std::uniform_int_distribution<size_t>(0, s.size() - 1)(rng_)] ^= char(1 << std::uniform_int_distribution<int>(0, 6)(rng_));
      ++injected_;
    }
    if (s.size() > 1 && u(rng_) < faults_.cut) {
      s.resize(std::uniform_int_distribution<size_t>(1, s.size() - 1)(rng_));
      ++injected_;
    }
    if (from == dev_master_ && faults_.delay_ms > 0) {
      held_.push_back({std::chrono::steady_clock::now() + std::chrono::milliseconds(faults_.delay_ms), s});
      return;
    }
    write_out(to, s);
  }

  void run() {
    while (!stop_) {
      int dev, cli;
      {
        std::lock_guard<std::mutex> lk(mu_);
        dev = dev_master_;
        cli = client_master_;
      }
      // A negative fd is ignored by poll: an unplugged side simply has no events.
      int wait_ms;
      {
        std::lock_guard<std::mutex> lk(mu_);
        wait_ms = release_held();
      }
      pollfd p[3] = {{wake_[0], POLLIN, 0}, {cli, POLLIN, 0}, {dev, POLLIN, 0}};
      ::poll(p, 3, wait_ms < 0 ? 1000 : std::min(wait_ms, 1000));
      char c[16];
      while (::read(wake_[0], c, sizeof c) > 0) {
      }
      std::lock_guard<std::mutex> lk(mu_);
      if (dev != dev_master_ || cli != client_master_) continue;  // unplugged or replugged meanwhile
      if (cli >= 0 && (p[1].revents & POLLIN)) forward(client_master_, dev_master_);
      if (dev >= 0 && (p[2].revents & POLLIN)) forward(dev_master_, client_master_);
    }
  }

  std::string folder_;
  std::mt19937 rng_;
  std::mutex mu_;
  Faults faults_;
  std::deque<Held> held_;
  int client_master_ = -1, dev_master_ = -1, client_hold_ = -1, dev_hold_ = -1;
  int wake_[2] = {-1, -1};
  std::atomic<bool> stop_{false};
  std::atomic<uint64_t> injected_{0};
  std::thread thread_;
};

// A device that answers late but in order, for the tests that a late reply is never taken
// for the next request (the FATEK, TRi and Modbus bridges, FUN150): a PtyProxy in a fresh
// folder that holds each of the device's replies back delay_ms. The device (a server)
// opens device_link(), the master client_link().
class LateDeviceLine {
 public:
  explicit LateDeviceLine(int delay_ms) : proxy_(dir_.path(), 1) { set_delay_ms(delay_ms); }
  std::string device_link() const { return proxy_.device_link(); }
  std::string client_link() const { return proxy_.client_link(); }
  // 0: the device answers in time again.
  void set_delay_ms(int ms) {
    PtyProxy::Faults f;
    f.delay_ms = ms;
    proxy_.set_faults(f);
  }

 private:
  TempDir dir_;
  PtyProxy proxy_;  // after dir_: gone before its folder is removed
};
