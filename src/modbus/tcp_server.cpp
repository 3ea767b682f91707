#include "plc_cell/modbus/tcp_server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"
#include "plc_cell/io/connections.h"
#include "plc_cell/modbus/forwarder.h"
#include "plc_cell/modbus/slave_handler.h"

namespace plc_cell {
namespace modbus {

std::vector<uint8_t> tcp_exception(const std::vector<uint8_t>& f, uint8_t code) {
  return {f[0], f[1], 0, 0, 0, 3, f[6], uint8_t(f[7] | 0x80), code};
}

namespace {
using Clock = std::chrono::steady_clock;

// What the server keeps per connection: the bytes of the request being received.
// Reading into our own buffer (instead of peeking the socket) sees a peer's close
// as end of file at once, and costs one system call per request.
struct Rx {
  uint8_t buf[MODBUS_TCP_MAX_ADU_LENGTH];
  int have = 0;
};

// A frame in the first `have` bytes: its length, 0 if not all there yet, -1 for a
// header no Modbus/TCP peer sends (the stream cannot be resynchronised: close).
int frame_length(const uint8_t* b, int have) {
  if (have < 6) return 0;
  const int proto = b[2] << 8 | b[3], length = b[4] << 8 | b[5];
  if (proto != 0 || length < 2 || length > MODBUS_TCP_MAX_ADU_LENGTH - 6) return -1;
  return have >= 6 + length ? 6 + length : 0;
}
}  // namespace

TcpServer::TcpServer(Plc& plc, TcpServerOptions opt) : plc_(plc), opt_(std::move(opt)) {}

TcpServer::~TcpServer() { stop(); }

void TcpServer::start() {
  if (thread_.joinable()) return;
  ctx_ = modbus_new_tcp(opt_.host.c_str(), opt_.port);
  if (!ctx_) throw Error("Modbus TCP " + opt_.host + ":" + std::to_string(opt_.port) + ": " + modbus_strerror(errno));
  listen_fd_ = modbus_tcp_listen(ctx_, 16);
  if (listen_fd_ < 0) {
    const std::string why = modbus_strerror(errno);
    modbus_free(ctx_);
    ctx_ = nullptr;
    throw Error("Modbus TCP " + opt_.host + ":" + std::to_string(opt_.port) + ": cannot listen: " + why);
  }
  // Non-blocking: the loop accepts until EAGAIN, a bounded batch per wake-up.
  fcntl(listen_fd_, F_SETFL, fcntl(listen_fd_, F_GETFL) | O_NONBLOCK);
  sockaddr_in sa{};
  socklen_t sl = sizeof sa;
  getsockname(listen_fd_, reinterpret_cast<sockaddr*>(&sa), &sl);
  port_ = ntohs(sa.sin_port);
  if (pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) throw Error("Modbus TCP: pipe: " + std::string(strerror(errno)));
  {
    std::lock_guard<std::mutex> lk(mu_);
    st_.running = true;
  }
  stop_ = false;
  thread_ = std::thread([this] { run(); });
}

void TcpServer::stop() {
  if (!thread_.joinable()) return;
  stop_ = true;
  const char c = 0;
  (void)!write(wake_[1], &c, 1);
  thread_.join();
  close(wake_[0]);
  close(wake_[1]);
  close(listen_fd_);
  modbus_free(ctx_);
  ctx_ = nullptr;
  listen_fd_ = -1;
  std::lock_guard<std::mutex> lk(mu_);
  st_.running = false;
  st_.connections = 0;
}

std::string TcpServer::describe() const {
  return "Modbus TCP " + opt_.host + ":" + std::to_string(port_ ? port_ : opt_.port);
}

ServerStatus TcpServer::status() const {
  std::lock_guard<std::mutex> lk(mu_);
  return st_;
}

void TcpServer::complete(uint64_t conn, std::vector<uint8_t> reply) {
  {
    std::lock_guard<std::mutex> lk(done_mu_);
    done_.emplace_back(conn, std::move(reply));
  }
  const char c = 1;
  (void)!write(wake_[1], &c, 1);
}

void TcpServer::run() {
  Connections<Rx> conns(ConnectionLimits{opt_.max_connections, opt_.idle_timeout_ms, opt_.frame_timeout_ms});
  const auto count = [&](bool ok, const std::string& err = {}) {
    std::lock_guard<std::mutex> lk(mu_);
    (ok ? st_.requests : st_.rejected)++;
    if (!err.empty()) st_.last_error = err;
  };
  const auto own = [&](uint8_t unit) {
    return !opt_.forwarder || unit == opt_.own_unit || unit == 0 || unit == 255;
  };
  // A reply goes out with one non-blocking send: a client that leaves its replies
  // unread until its socket buffer is full is closed, not waited for.
  const auto send_all = [](int fd, const uint8_t* p, size_t n) {
    return ::send(fd, p, n, MSG_NOSIGNAL | MSG_DONTWAIT) == ssize_t(n);
  };
  uint8_t rsp[MODBUS_TCP_MAX_ADU_LENGTH];
  // Answers every whole frame in the connection's buffer (a client may pipeline);
  // true when the connection must be closed.
  const auto serve = [&](Connections<Rx>::Conn& c, Clock::time_point now) {
    Rx& rx = c.x;
    bool closing = false;
    for (;;) {
      const int flen = frame_length(rx.buf, rx.have);
      if (flen < 0) {
        count(false, "malformed MBAP header");
        closing = true;
        break;
      }
      if (flen == 0) break;
      Connections<Rx>::complete(c, now);
      const uint8_t* f = rx.buf;
      if (!own(f[6])) {  // gateway: the RTU side answers, in its own time
        std::vector<uint8_t> frame(f, f + flen);
        const uint64_t id = c.id;
        c.waiting = true;
        if (!opt_.forwarder->submit(id, frame, [this](uint64_t conn, std::vector<uint8_t> r) { complete(conn, std::move(r)); })) {
          c.waiting = false;
          const auto busy = tcp_exception(frame, MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY);
          closing = !send_all(c.fd, busy.data(), busy.size());
          count(false, "gateway busy");
        } else {
          count(true);
        }
      } else {
        // MBAP delimits the frame, so a bad PDU is consumed whole and answered
        // with an exception; the connection stays in step.
        const PduAnswer a = answer_pdu(plc_, f + 7, flen - 7, rsp + 7, &opt_.writable);
        std::memcpy(rsp, f, 7);
        rsp[2] = rsp[3] = 0;
        rsp[4] = uint8_t((a.length + 1) >> 8);
        rsp[5] = uint8_t(a.length + 1);
        closing = !send_all(c.fd, rsp, size_t(7 + a.length));
        if (a.accepted) count(true);
        else if (a.exception == MODBUS_EXCEPTION_ILLEGAL_FUNCTION) count(false, "illegal function " + std::to_string(f[7]));
        else count(false, "exception " + std::to_string(a.exception) + " to function " + std::to_string(f[7]));
        if (closing) count(false, std::string("reply: ") + strerror(errno));
      }
      rx.have -= flen;
      if (rx.have) std::memmove(rx.buf, rx.buf + flen, size_t(rx.have));
      if (closing || c.waiting) break;  // a forwarded request keeps the order: read on after its reply
    }
    return closing;
  };
  std::vector<pollfd> pfds;  // reused: no allocation per request
  std::vector<int> to_close;
  size_t reported = 0;
  while (!stop_) {
    pfds.clear();
    pfds.push_back({wake_[0], POLLIN, 0});
    pfds.push_back({listen_fd_, POLLIN, 0});
    for (const auto& c : conns.all()) pfds.push_back({c.fd, short(c.waiting ? 0 : POLLIN), 0});
    if (poll(pfds.data(), pfds.size(), conns.poll_timeout_ms(Clock::now())) < 0 && errno != EINTR) break;
    if (pfds[0].revents) {
      char buf[64];
      while (read(wake_[0], buf, sizeof buf) > 0) {
      }
      if (stop_) break;
      std::deque<std::pair<uint64_t, std::vector<uint8_t>>> done;
      {
        std::lock_guard<std::mutex> lk(done_mu_);
        done.swap(done_);
      }
      for (auto& d : done)
        for (auto& c : conns.all())
          if (c.id == d.first) {  // gone meanwhile: the reply is dropped
            c.waiting = false;
            // Requests that came in meanwhile are answered now, in order.
            if (!send_all(c.fd, d.second.data(), d.second.size()) || serve(c, Clock::now())) {
              c.waiting = true;  // skipped below; closed after the loop
              to_close.push_back(c.fd);
            }
          }
    }
    const auto now = Clock::now();
    for (size_t i = 2; i < pfds.size(); ++i) {
      auto& c = conns.all()[i - 2];
      if (c.waiting) continue;
      if (pfds[i].revents & (POLLIN | POLLHUP | POLLERR)) {
        Rx& rx = c.x;
        const ssize_t n = recv(c.fd, rx.buf + rx.have, sizeof rx.buf - size_t(rx.have), MSG_DONTWAIT);
        if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
          if (rx.have) count(false, "connection closed in the middle of a request");
          to_close.push_back(c.fd);
          continue;
        }
        if (n > 0) rx.have += int(n);
        const bool closing = serve(c, now);
        if (closing) {
          to_close.push_back(c.fd);
          continue;
        }
        if (rx.have) Connections<Rx>::partial(c, now);
      }
      switch (conns.expired(c, now)) {
        case Connections<Rx>::Expiry::Frame:
          count(false, "request not complete within the frame timeout");
          to_close.push_back(c.fd);
          break;
        case Connections<Rx>::Expiry::Idle: to_close.push_back(c.fd); break;
        case Connections<Rx>::Expiry::None: break;
      }
    }
    for (int fd : to_close) {
      close(fd);
      conns.remove_fd(fd);
    }
    to_close.clear();
    if (pfds[1].revents & POLLIN) {
      for (int k = 0; k < 16; ++k) {  // bounded: the clients we have are served in between
        const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
        if (fd < 0) break;
        int evicted = -1;
        const auto how = conns.admit(fd, Clock::now(), &evicted);
        if (how == Connections<Rx>::Admit::Refused) {
          close(fd);  // bounded: refuse rather than starve the ones we have
          count(false, "connection refused: " + std::to_string(opt_.max_connections) + " already open");
          continue;
        }
        if (how == Connections<Rx>::Admit::Evicted) {
          close(evicted);
          count(false, "connection closed for a new client: no complete request within the frame timeout");
        }
        const int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      }
    }
    if (conns.size() != reported) {
      reported = conns.size();
      std::lock_guard<std::mutex> lk(mu_);
      st_.connections = reported;
    }
  }
  for (const auto& c : conns.all()) close(c.fd);
}

}  // namespace modbus
}  // namespace plc_cell
