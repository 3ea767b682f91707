#pragma once
// A master's link to one device, owned by one thread (the FATEK and TRi bridges): the
// thread connects (and confirms that a device answers), runs each poll when it is due,
// reconnects with back-off (io/backoff.h) when the link breaks, and lets the front end's
// transactions in between two polls: the lines are half-duplex, so there is one
// transaction at a time. The protocol is the derived class's: its transport, how a
// device is confirmed, its polls and its transactions.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/io/transport.h"

namespace plc_cell {

struct LinkStatus {
  bool connected = false;
  std::string last_error;  // "" until something fails, and after recover()
  uint64_t errors = 0, polls = 0, reconnects = 0;
  double latency_last_ms = 0, latency_max_ms = 0;  // of the counted poll (count_poll)
  // Polls that failed since the last one that delivered (not reset by a reconnection: a
  // device that answers the confirmation but garbles every poll keeps counting), and
  // whether any poll delivered yet.
  uint64_t failed_polls_in_row = 0;
  bool delivered = false;
};

// What the link's state means for its diagnostics: OK only while polls deliver. A link
// that is down is ERROR; one that is up but whose last kLinkErrorPolls polls (or more)
// failed is ERROR too (it delivers nothing, however often it reconnects); one whose
// last poll (or two) failed is WARN.
constexpr uint64_t kLinkErrorPolls = 3;
enum class LinkLevel { Ok, Warn, Error };
struct LinkHealth {
  LinkLevel level;
  std::string message;
};
LinkHealth link_health(const LinkStatus& s);

// What a bridge's polls report (the shapes of plc_node's topics). One poll of the I/O
// image: the RUN flag, X0..X255 (inputs), Y0..Y255 (outputs) and each named signal.
struct IoResult {
  bool ok = false;
  std::string error;
  bool run = false;
  std::vector<bool> x, y;     // 256 each
  std::vector<bool> signals;  // per the bridge's signals
};

// One poll of one register group: every element of its spans, in their order.
struct GroupResult {
  size_t group = 0;
  bool ok = false;
  std::string error;
  std::vector<uint32_t> values;
};

class PolledLink {
 public:
  virtual ~PolledLink();
  PolledLink(const PolledLink&) = delete;
  PolledLink& operator=(const PolledLink&) = delete;

  void start();
  // A derived class calls it in its destructor, before the members its polls reach go.
  void stop();
  // Drops the link and reconnects now, back-off reset.
  void recover();
  LinkStatus status() const;
  // "tcp 127.0.0.1:500 station 1"
  const std::string& describe() const { return link_name_; }

 protected:
  using Clock = std::chrono::steady_clock;
  // on_error: every failure counted in status().errors (may be empty).
  PolledLink(double backoff_min_s, double backoff_max_s, std::function<void(const std::string&)> on_error);

  virtual Transport& transport() = 0;
  // Called with the link lock held on a newly opened transport: an open transport is not
  // proof of a device (a TCP gateway accepts with nothing behind it, a serial port opens
  // with no cable), so the link counts only once this got an answer. Throws when not.
  virtual void confirm() = 0;

  // A poll due at rate_hz; body runs on the link's thread, no lock held, and returns false
  // when the link broke (the round ends, the next turn reconnects).
  void add_poll(double rate_hz, std::function<bool()> body);

  // One front-end transaction under the link lock, connecting first if need be (worth an
  // attempt now, whatever the back-off: someone waits for it). A CommError drops the link.
  template <typename F>
  auto transaction(F&& f) -> decltype(f()) {
    std::lock_guard<std::mutex> lk(link_mu_);
    if (!connect_locked()) throw CommError(link_name_ + " is not connected: " + status().last_error);
    try {
      return f();
    } catch (const CommError& e) {
      fail(e.what());
      drop_link();
      throw;
    }
  }

  // One poll's transactions, link lock held. A communication error drops the link (false);
  // any other error (the device refused a request) fails this poll only.
  template <typename F>
  bool polled(std::string* error, F&& body) {
    try {
      body();
      return true;
    } catch (const CommError& e) {
      *error = e.what();
      fail(*error);
      drop_link();
      return false;
    } catch (const std::exception& e) {
      *error = e.what();
      fail(*error);
      return true;
    }
  }

  // One poll into r (an IoResult, a GroupResult): body runs under the link lock unless the
  // link was dropped meanwhile (recover(): the transport would reopen by itself,
  // unconfirmed; false, nothing reported); then r goes to sink, failed or not (r.ok).
  // Returns false when the link broke.
  template <typename R, typename F>
  bool poll_into(R& r, const std::function<void(const R&)>& sink, F&& body) {
    bool up;
    {
      std::lock_guard<std::mutex> lk(link_mu_);
      if (!transport().is_open()) return false;
      up = polled(&r.error, [&] {
        body();
        r.ok = true;
      });
    }
    count_delivery(r.ok);
    if (sink) sink(r);
    return up;
  }

  // A poll that counts in status(): polls and latency.
  void count_poll(double ms);
  // Every poll's outcome: the failed polls in a row (link_health).
  void count_delivery(bool ok);
  void fail(const std::string& what);
  // Link lock held: the link broke, the next turn reconnects.
  void drop_link();

  std::mutex link_mu_;     // one transaction at a time on the half-duplex link
  std::string link_name_;  // set by the derived class's constructor

 private:
  struct Poll {
    Clock::duration period;
    Clock::time_point due;
    std::function<bool()> body;
  };
  void run();
  bool connect_locked();

  double backoff_min_s_, backoff_max_s_;
  std::function<void(const std::string&)> on_error_;
  std::vector<Poll> polls_;
  mutable std::mutex state_mu_;
  std::condition_variable cv_;
  bool stopping_ = false, recover_ = false;
  LinkStatus status_;
  std::thread thread_;
};

}  // namespace plc_cell
