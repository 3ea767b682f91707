#pragma once
// A TCP proxy between a FATEK master and its PLC that counts the requests and misbehaves on
// demand: it drops every connection and refuses new ones, garbles every reply (a well-framed
// answer to another command), swallows the replies, or holds them back (a late device). At
// a chosen request it can signal a process: the kill test stops the runner there, at a
// point of the protocol rather than of the clock.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

class FatekProxy {
 public:
  enum class Mode { Forward, Refuse, Garble, Silent, Late };

  explicit FatekProxy(int upstream_port) : upstream_(upstream_port) {
    listen_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    int one = 1;
    ::setsockopt(listen_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (::bind(listen_, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0 || ::listen(listen_, 8) != 0)
      throw std::runtime_error("proxy: cannot listen");
    socklen_t len = sizeof a;
    ::getsockname(listen_, reinterpret_cast<sockaddr*>(&a), &len);
    port_ = ntohs(a.sin_port);
    if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) throw std::runtime_error("proxy: pipe");
    thread_ = std::thread([this] { run(); });
  }
  ~FatekProxy() {
    stop_ = true;
    poke();
    thread_.join();
    for (auto& p : pairs_) p.close();
    ::close(listen_);
    ::close(wake_[0]);
    ::close(wake_[1]);
  }

  int port() const { return port_; }
  void set_mode(Mode m, int late_ms = 0) {
    std::lock_guard<std::mutex> lk(mu_);
    mode_ = m;
    late_ms_ = late_ms;
    poke();
  }
  // Sends sig to pid once the n-th request (counted from the proxy's start) has gone upstream.
  void signal_at(uint64_t n, pid_t pid, int sig) {
    std::lock_guard<std::mutex> lk(mu_);
    fired_ = false;
    signal_at_ = n;
    signal_pid_ = pid;
    signal_ = sig;
  }
  // Switches to mode once the n-th request has gone upstream.
  void mode_at(uint64_t n, Mode m, int late_ms = 0) {
    std::lock_guard<std::mutex> lk(mu_);
    mode_at_ = n;
    next_mode_ = m;
    next_late_ms_ = late_ms;
  }
  uint64_t requests() const { return requests_; }
  // Whether the signal of signal_at() went out.
  bool fired() const { return fired_; }

 private:
  struct Held {
    std::chrono::steady_clock::time_point due;
    std::string bytes;
  };
  struct Pair {
    int client = -1, server = -1;
    std::string from_server;  // an unfinished reply frame (garbling works on whole frames)
    std::deque<Held> held;
    void close() {
      if (client >= 0) ::close(client);
      if (server >= 0) ::close(server);
      client = server = -1;
    }
  };

  void poke() { (void)!::write(wake_[1], "x", 1); }

  int connect_upstream() {
    const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    a.sin_port = htons(uint16_t(upstream_));
    if (::connect(s, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
      ::close(s);
      return -1;
    }
    return s;
  }

  static void send_all(int fd, const std::string& s) {
    size_t off = 0;
    while (off < s.size()) {
      const ssize_t w = ::send(fd, s.data() + off, s.size() - off, MSG_NOSIGNAL);
      if (w <= 0) return;
      off += size_t(w);
    }
  }

  // A reply frame STX ss cc ... LRC ETX made an answer to command 4E (the LRC made again).
  static std::string garble(std::string f) {
    if (f.size() < 8) return f;
    f[3] = '4';
    f[4] = 'E';
    unsigned sum = 0;
    for (size_t i = 0; i + 3 < f.size(); ++i) sum += static_cast<unsigned char>(f[i]);
    char lrc[3];
    std::snprintf(lrc, sizeof lrc, "%02X", sum & 0xFF);
    f[f.size() - 3] = lrc[0];
    f[f.size() - 2] = lrc[1];
    return f;
  }

  void from_client(Pair& p) {
    char buf[1024];
    const ssize_t n = ::recv(p.client, buf, sizeof buf, 0);
    if (n <= 0) return p.close();
    send_all(p.server, std::string(buf, size_t(n)));
    for (ssize_t i = 0; i < n; ++i) {
      if (buf[i] != 0x03) continue;
      const uint64_t r = ++requests_;
      if (signal_at_ && r >= signal_at_ && signal_pid_ > 0) {
        // Said before it goes: the test wakes as soon as the runner dies and asks at once.
        fired_ = true;
        signal_at_ = 0;
        ::kill(signal_pid_, signal_);
      }
      if (r == mode_at_) {
        mode_ = next_mode_;
        late_ms_ = next_late_ms_;
      }
    }
  }

  void from_server(Pair& p) {
    char buf[1024];
    const ssize_t n = ::recv(p.server, buf, sizeof buf, 0);
    if (n <= 0) return p.close();
    p.from_server.append(buf, size_t(n));
    for (size_t etx; (etx = p.from_server.find('\x03')) != std::string::npos;) {
      std::string frame = p.from_server.substr(0, etx + 1);
      p.from_server.erase(0, etx + 1);
      if (mode_ == Mode::Silent) continue;
      if (mode_ == Mode::Garble) frame = garble(frame);
      if (mode_ == Mode::Late) {
        p.held.push_back({std::chrono::steady_clock::now() + std::chrono::milliseconds(late_ms_), frame});
        continue;
      }
      send_all(p.client, frame);
    }
  }

  // The held replies that are due; the ms until the next (-1: none).
  int release_held() {
    int next = -1;
    const auto now = std::chrono::steady_clock::now();
    for (auto& p : pairs_) {
      while (!p.held.empty() && p.held.front().due <= now) {
        if (p.client >= 0) send_all(p.client, p.held.front().bytes);
        p.held.pop_front();
      }
      if (!p.held.empty()) {
        const int ms = int(std::chrono::duration_cast<std::chrono::milliseconds>(p.held.front().due - now).count()) + 1;
        next = next < 0 ? ms : std::min(next, ms);
      }
    }
    return next;
  }

  void accept_one() {
    const int c = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
    if (c < 0) return;
    const int s = mode_ == Mode::Refuse ? -1 : connect_upstream();
    if (s < 0) {
      ::close(c);
      return;
    }
    Pair p;
    p.client = c;
    p.server = s;
    pairs_.push_back(p);
  }

  void run() {
    while (!stop_) {
      std::vector<pollfd> fds = {{wake_[0], POLLIN, 0}, {listen_, POLLIN, 0}};
      int wait_ms;
      {
        std::lock_guard<std::mutex> lk(mu_);
        if (mode_ == Mode::Refuse)
          for (auto& p : pairs_) p.close();
        pairs_.erase(std::remove_if(pairs_.begin(), pairs_.end(), [](const Pair& p) { return p.client < 0; }),
                     pairs_.end());
        for (auto& p : pairs_) fds.push_back({p.client, POLLIN, 0}), fds.push_back({p.server, POLLIN, 0});
        wait_ms = release_held();
      }
      ::poll(fds.data(), fds.size(), wait_ms < 0 ? 200 : std::min(wait_ms, 200));
      char c[16];
      while (::read(wake_[0], c, sizeof c) > 0) {
      }
      std::lock_guard<std::mutex> lk(mu_);
      if (fds[1].revents & POLLIN) accept_one();
      for (size_t i = 0; i < (fds.size() - 2) / 2 && i < pairs_.size(); ++i) {
        if (pairs_[i].client >= 0 && (fds[2 + 2 * i].revents & (POLLIN | POLLHUP))) from_client(pairs_[i]);
        if (pairs_[i].server >= 0 && (fds[3 + 2 * i].revents & (POLLIN | POLLHUP))) from_server(pairs_[i]);
      }
    }
  }

  int upstream_;
  int listen_ = -1, port_ = 0;
  int wake_[2] = {-1, -1};
  std::mutex mu_;
  Mode mode_ = Mode::Forward;
  int late_ms_ = 0;
  uint64_t signal_at_ = 0, mode_at_ = 0;
  pid_t signal_pid_ = -1;
  int signal_ = SIGTERM;
  Mode next_mode_ = Mode::Forward;
  int next_late_ms_ = 0;
  std::atomic<uint64_t> requests_{0};
  std::atomic<bool> fired_{false};
  std::vector<Pair> pairs_;
  std::atomic<bool> stop_{false};
  std::thread thread_;
};
