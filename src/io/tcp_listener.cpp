#include "plc_cell/io/tcp_listener.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "plc_cell/core/error.h"
#include "close_fd.h"

namespace plc_cell {
namespace {

using Clock = std::chrono::steady_clock;

struct Rx {
  std::string in, out;
  std::unique_ptr<TcpProtocol::Session> session;
  bool closing = false;  // closed after this turn; skipped meanwhile
};
using Table = Connections<Rx>;

}  // namespace

TcpListener::TcpListener(TcpProtocol& protocol, TcpListenerOptions opt) : protocol_(protocol), opt_(std::move(opt)) {
  if (opt_.host.empty()) opt_.host = "127.0.0.1";
}

TcpListener::~TcpListener() { stop(); }

void TcpListener::start() {
  if (running_) return;
  addrinfo hints{}, *res = nullptr;
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  const std::string where = opt_.name + " " + opt_.host + ":" + std::to_string(opt_.port);
  if (getaddrinfo(opt_.host.c_str(), std::to_string(opt_.port).c_str(), &hints, &res) != 0 || !res)
    throw Error(where + ": cannot resolve host");
  listen_fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK | SOCK_CLOEXEC, 0);
  int one = 1;
  setsockopt(listen_fd_, SOL_SOCKET, SO_REUSEADDR, &one, sizeof one);
  if (::bind(listen_fd_, res->ai_addr, res->ai_addrlen) != 0 || ::listen(listen_fd_, 16) != 0) {
    const int err = errno;
    freeaddrinfo(res);
    close_fd(listen_fd_);
    throw Error(where + ": cannot listen: " + std::strerror(err));
  }
  freeaddrinfo(res);
  sockaddr_in sa{};
  socklen_t len = sizeof sa;
  getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&sa), &len);
  bound_port_ = ntohs(sa.sin_port);
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) {
    const int err = errno;
    close_fd(listen_fd_);
    throw Error(where + ": pipe: " + std::strerror(err));
  }
  {
    std::lock_guard<std::mutex> lk(done_mu_);
    done_.clear();
  }
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void TcpListener::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  close_fd(listen_fd_);
  close_fd(wake_[0]);
  close_fd(wake_[1]);
}

void TcpListener::deliver(uint64_t conn, std::string reply) {
  {
    std::lock_guard<std::mutex> lk(done_mu_);
    done_.emplace_back(conn, std::move(reply));
  }
  (void)!::write(wake_[1], "d", 1);
}

namespace {

// The listener's thread: the state of its poll() loop and the steps of one turn.
class Loop {
 public:
  using Done = std::vector<std::pair<uint64_t, std::string>>;
  Loop(TcpProtocol& protocol, const TcpListenerOptions& opt, int listen_fd, int wake_fd)
      : protocol_(protocol), opt_(opt), listen_fd_(listen_fd), wake_fd_(wake_fd), conns_(opt.limits), rbuf_(opt.max_input) {}
  ~Loop() {
    for (const auto& c : conns_.all()) ::close(c.fd);
    if (reported_) protocol_.on_connections(0);
  }

  // One turn: false when poll() failed.
  bool turn(const std::atomic<bool>& running, std::mutex& done_mu, Done& done) {
    pfds_.clear();
    pfds_.push_back({wake_fd_, POLLIN, 0});
    pfds_.push_back({listen_fd_, POLLIN, 0});
    for (const auto& c : conns_.all())
      pfds_.push_back({c.fd, short((c.waiting ? 0 : POLLIN) | (c.x.out.empty() ? 0 : POLLOUT)), 0});
    if (::poll(pfds_.data(), pfds_.size(), conns_.poll_timeout_ms(Clock::now())) < 0 && errno != EINTR) return false;
    if (!running) return true;
    if (pfds_[0].revents) take_done(done_mu, done);
    serve_clients(Clock::now());
    for (int fd : to_close_) {
      ::close(fd);
      conns_.remove_fd(fd);
    }
    to_close_.clear();
    if (pfds_[1].revents & POLLIN) accept_clients();
    if (conns_.size() != reported_) {
      reported_ = conns_.size();
      protocol_.on_connections(reported_);
    }
    return true;
  }

 private:
  // One non-blocking send of what is pending; false when the connection must be closed.
  bool flush(Table::Conn& c) {
    std::string& out = c.x.out;
    if (out.empty()) return true;
    const ssize_t w = ::send(c.fd, out.data(), out.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    const int err = errno;
    if (w > 0) out.erase(0, size_t(w));
    else if (w < 0 && err != EAGAIN && err != EINTR) {
      protocol_.on_event(TcpProtocol::Event::ReplyFailed, err);
      return false;
    }
    if (out.size() > opt_.max_pending_output) {
      protocol_.on_event(TcpProtocol::Event::SlowReader, err);
      return false;
    }
    return true;
  }

  // Lets the protocol answer what is buffered, its replies going out between turns;
  // false when the connection must be closed.
  bool serve(Table::Conn& c, Clock::time_point now) {
    for (;;) {
      const TcpProtocol::Taken t = protocol_.take(c.id, c.x.session.get(), c.x.in, c.x.out);
      if (t.requests) Table::complete(c, now);
      if (t.bad) return false;
      if (t.waiting) c.waiting = true;
      if (!flush(c)) return false;
      if (t.partial) Table::partial(c, now);
      if (!t.requests || c.waiting) return true;  // a waiting request keeps the order: read on after its reply
    }
  }

  void close_later(Table::Conn& c) {
    c.x.closing = true;
    to_close_.push_back(c.fd);
  }

  // The replies deliver() handed over.
  void take_done(std::mutex& done_mu, Done& done) {
    char buf[64];
    while (::read(wake_fd_, buf, sizeof buf) > 0) {
    }
    {
      std::lock_guard<std::mutex> lk(done_mu);
      done_.swap(done);
    }
    for (auto& d : done_)
      for (auto& c : conns_.all())
        if (c.id == d.first && !c.x.closing) {  // gone meanwhile: the reply is dropped
          c.waiting = false;
          c.x.out += d.second;
          // Requests that came in meanwhile are answered now, in order.
          if (!flush(c) || !serve(c, Clock::now())) close_later(c);
        }
    done_.clear();
  }

  // Reads, serves, flushes and times out each client polled this turn.
  void serve_clients(Clock::time_point now) {
    for (size_t i = 2; i < pfds_.size(); ++i) {
      auto& c = conns_.all()[i - 2];
      if (c.waiting || c.x.closing) continue;
      if ((pfds_[i].revents & (POLLIN | POLLHUP | POLLERR)) && !read_client(c, now)) {
        to_close_.push_back(c.fd);
        continue;
      }
      if (!c.x.out.empty() && !flush(c)) {
        to_close_.push_back(c.fd);
        continue;
      }
      switch (conns_.expired(c, now)) {
        case Table::Expiry::Frame:
          protocol_.on_event(TcpProtocol::Event::FrameTimeout, 0);
          to_close_.push_back(c.fd);
          break;
        case Table::Expiry::Idle: to_close_.push_back(c.fd); break;
        case Table::Expiry::None: break;
      }
    }
  }

  // false when the connection must be closed.
  bool read_client(Table::Conn& c, Clock::time_point now) {
    std::string& in = c.x.in;
    // A protocol takes or refuses a full buffer, so there is always room here.
    const size_t room = opt_.max_input - std::min(in.size(), opt_.max_input);
    const ssize_t n = room ? ::recv(c.fd, rbuf_.data(), room, MSG_DONTWAIT) : 0;
    if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
      if (!in.empty()) protocol_.on_event(TcpProtocol::Event::ClosedMidRequest, 0);
      return false;
    }
    if (n < 0) return true;
    in.append(rbuf_.data(), size_t(n));
    return serve(c, now);
  }

  void accept_clients() {
    for (int k = 0; k < 16; ++k) {  // bounded: the clients we have are served in between
      const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
      if (fd < 0) break;
      int evicted = -1;
      const auto how = conns_.admit(fd, Clock::now(), &evicted);
      if (how == Table::Admit::Refused) {
        ::close(fd);  // bounded: refuse rather than starve the ones we have
        protocol_.on_event(TcpProtocol::Event::Refused, 0);
        continue;
      }
      if (how == Table::Admit::Evicted) {
        ::close(evicted);
        protocol_.on_event(TcpProtocol::Event::Evicted, 0);
      }
      Rx& rx = conns_.all().back().x;
      rx.in.reserve(opt_.max_input);
      rx.session = protocol_.open();
      int one = 1;
      setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
    }
  }

  TcpProtocol& protocol_;
  const TcpListenerOptions& opt_;
  const int listen_fd_, wake_fd_;
  Table conns_;
  std::vector<pollfd> pfds_;  // reused: no allocation per request
  std::vector<int> to_close_;
  Done done_;
  std::vector<char> rbuf_;
  size_t reported_ = 0;
};

}  // namespace

void TcpListener::loop() {
  Loop l(protocol_, opt_, listen_fd_, wake_[0]);
  while (running_)
    if (!l.turn(running_, done_mu_, done_)) break;
}

}  // namespace plc_cell
