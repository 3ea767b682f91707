#pragma once
// The time bounds of a TCP server's client connections, shared by the FATEK and
// Modbus servers (one poll() thread each):
//  - frame deadline: a request that has begun must be complete within frame_timeout
//    of its first byte, or the connection is closed (a peer that sends part of a
//    frame and stalls, or trickles one byte a second, is not waited for);
//  - idle deadline: idle_timeout counts from the last complete request (or the
//    accept), not from the last byte, so bytes that never make a request do not
//    keep a connection alive;
//  - slots: when all max_connections are taken, a new client takes the slot of the
//    connection that has gone longest without completing a request, provided that
//    is longer than frame_timeout (evict_after_ms when given: the monitor's HTTP
//    server gives 0); otherwise the new client is refused. A client that keeps
//    completing requests is never evicted.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

namespace plc_cell {

struct ConnectionLimits {
  int max_connections = 16;
  int idle_timeout_ms = 60000;
  int frame_timeout_ms = 1000;
  int evict_after_ms = -1;  // how stale a connection must be to lose its slot (-1: frame_timeout_ms)
};

// Extra: what the server keeps per connection (buffers, decoder).
template <typename Extra>
class Connections {
 public:
  using Clock = std::chrono::steady_clock;
  struct Conn {
    int fd = -1;
    uint64_t id = 0;
    Clock::time_point last_request;  // last complete request, or the accept
    Clock::time_point frame_start;   // first byte of the unfinished request
    bool in_frame = false;
    bool waiting = false;            // the server has work out for it: no deadlines run
    Extra x{};
  };

  explicit Connections(ConnectionLimits l) : lim_(l) {}

  std::vector<Conn>& all() { return conns_; }
  size_t size() const { return conns_.size(); }
  const ConnectionLimits& limits() const { return lim_; }

  enum class Admit { Accepted, Evicted, Refused };
  // A new client. On Evicted, *evicted_fd is the connection to close (already out
  // of the table), and *evicted (if given) what the server kept for it; on Refused
  // the caller closes fd.
  Admit admit(int fd, Clock::time_point now, int* evicted_fd, Extra* evicted = nullptr) {
    *evicted_fd = -1;
    Admit how = Admit::Accepted;
    if (int(conns_.size()) >= lim_.max_connections) {
      auto oldest = conns_.end();
      for (auto it = conns_.begin(); it != conns_.end(); ++it)
        if (!it->waiting && (oldest == conns_.end() || it->last_request < oldest->last_request)) oldest = it;
      const int grace = lim_.evict_after_ms >= 0 ? lim_.evict_after_ms : lim_.frame_timeout_ms;
      if (oldest == conns_.end() || now - oldest->last_request < ms(grace)) return Admit::Refused;
      *evicted_fd = oldest->fd;
      if (evicted) *evicted = std::move(oldest->x);
      conns_.erase(oldest);
      how = Admit::Evicted;
    }
    Conn c;
    c.fd = fd;
    c.id = next_id_++;
    c.last_request = now;
    conns_.push_back(std::move(c));
    return how;
  }

  // Bytes of an unfinished request are buffered: starts the frame deadline.
  static void partial(Conn& c, Clock::time_point now) {
    if (!c.in_frame) c.frame_start = now;
    c.in_frame = true;
  }
  // A whole request was taken: the idle deadline restarts, the frame deadline stops.
  static void complete(Conn& c, Clock::time_point now) {
    c.last_request = now;
    c.in_frame = false;
  }

  enum class Expiry { None, Frame, Idle };
  Expiry expired(const Conn& c, Clock::time_point now) const {
    if (c.waiting) return Expiry::None;
    if (c.in_frame && now - c.frame_start >= ms(lim_.frame_timeout_ms)) return Expiry::Frame;
    if (now - c.last_request >= ms(lim_.idle_timeout_ms)) return Expiry::Idle;
    return Expiry::None;
  }

  // poll() timeout until the nearest deadline, in ms (-1: none).
  int poll_timeout_ms(Clock::time_point now) const {
    Clock::time_point next = Clock::time_point::max();
    for (const auto& c : conns_) {
      if (c.waiting) continue;
      next = std::min(next, c.last_request + ms(lim_.idle_timeout_ms));
      if (c.in_frame) next = std::min(next, c.frame_start + ms(lim_.frame_timeout_ms));
    }
    if (next == Clock::time_point::max()) return -1;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count();
    return int(std::max<long long>(left, 0) + 1);
  }

  void remove_fd(int fd) {
    conns_.erase(std::remove_if(conns_.begin(), conns_.end(), [fd](const Conn& c) { return c.fd == fd; }),
                 conns_.end());
  }

 private:
  static std::chrono::milliseconds ms(int v) { return std::chrono::milliseconds(v); }
  ConnectionLimits lim_;
  std::vector<Conn> conns_;
  uint64_t next_id_ = 1;
};

}  // namespace plc_cell
