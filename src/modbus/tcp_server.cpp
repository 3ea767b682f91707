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
#include "plc_cell/modbus/forwarder.h"
#include "plc_cell/modbus/slave_handler.h"

namespace plc_cell {
namespace modbus {

std::vector<uint8_t> tcp_exception(const std::vector<uint8_t>& f, uint8_t code) {
  return {f[0], f[1], 0, 0, 0, 3, f[6], uint8_t(f[7] | 0x80), code};
}

namespace {
using Clock = std::chrono::steady_clock;

struct Conn {
  int fd;
  uint64_t id;
  Clock::time_point last;
  bool waiting = false;  // a forwarded request is out: read nothing more, keep order
};

enum class Frame { Partial, Ready, Closed, Bad };

// Looks at the MBAP header without consuming: a whole frame there, not yet, or a
// header no Modbus/TCP peer sends (the stream cannot be resynchronised: close).
Frame peek_frame(int fd, uint8_t* buf, int* frame_len) {
  const ssize_t n = recv(fd, buf, MODBUS_TCP_MAX_ADU_LENGTH, MSG_PEEK | MSG_DONTWAIT);
  if (n == 0) return Frame::Closed;
  if (n < 0) return (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR) ? Frame::Partial : Frame::Closed;
  if (n < 6) return Frame::Partial;
  const int proto = buf[2] << 8 | buf[3], length = buf[4] << 8 | buf[5];
  if (proto != 0 || length < 2 || length > MODBUS_TCP_MAX_ADU_LENGTH - 6) return Frame::Bad;
  *frame_len = 6 + length;
  return n >= *frame_len ? Frame::Ready : Frame::Partial;
}

// The frame length a supported request must have, from its own fields; checked
// before libmodbus reads it, which sizes frames by function code and would
// otherwise wait for bytes that never come or eat into the next frame.
bool well_formed(const uint8_t* f, int len) {
  switch (f[7]) {
    case 15: case 16: return len >= 13 && len == 7 + 6 + f[12];
    case 23: return len >= 17 && len == 7 + 10 + f[16];
    default: return len == 7 + 5;
  }
}

void drain(int fd, int bytes) {
  uint8_t buf[MODBUS_TCP_MAX_ADU_LENGTH];
  while (bytes > 0) {
    const ssize_t n = recv(fd, buf, std::min<size_t>(sizeof buf, size_t(bytes)), MSG_DONTWAIT);
    if (n <= 0) return;
    bytes -= int(n);
  }
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
  std::vector<Conn> conns;
  uint64_t next_id = 1;
  uint8_t req[MODBUS_TCP_MAX_ADU_LENGTH];
  const auto idle = std::chrono::milliseconds(opt_.idle_timeout_ms);
  const auto count = [&](bool ok, const std::string& err = {}) {
    std::lock_guard<std::mutex> lk(mu_);
    (ok ? st_.requests : st_.rejected)++;
    if (!err.empty()) st_.last_error = err;
  };
  const auto own = [&](uint8_t unit) {
    return !opt_.forwarder || unit == opt_.own_unit || unit == 0 || unit == 255;
  };
  std::vector<pollfd> pfds;  // reused: no allocation per request
  std::vector<int> to_close;
  size_t reported = 0;
  while (!stop_) {
    pfds.clear();
    pfds.push_back({wake_[0], POLLIN, 0});
    pfds.push_back({listen_fd_, POLLIN, 0});
    for (const auto& c : conns) pfds.push_back({c.fd, short(c.waiting ? 0 : POLLIN), 0});
    int timeout = -1;
    const auto now = Clock::now();
    for (const auto& c : conns) {
      if (c.waiting) continue;
      const long left = std::max<long>(
          std::chrono::duration_cast<std::chrono::milliseconds>(c.last + idle - now).count(), 0) + 1;
      timeout = timeout < 0 ? int(left) : std::min(timeout, int(left));
    }
    if (poll(pfds.data(), pfds.size(), timeout) < 0 && errno != EINTR) break;
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
        for (auto& c : conns)
          if (c.id == d.first) {  // gone meanwhile: the reply is dropped
            (void)!send(c.fd, d.second.data(), d.second.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
            c.waiting = false;
            c.last = Clock::now();
          }
    }
    to_close.clear();
    for (size_t i = 2; i < pfds.size(); ++i) {
      Conn& c = conns[i - 2];
      if (c.waiting) continue;
      if (!(pfds[i].revents & (POLLIN | POLLHUP | POLLERR))) {
        if (Clock::now() - c.last >= idle) to_close.push_back(c.fd);
        continue;
      }
      c.last = Clock::now();
      int frame_len = 0;
      const Frame f = peek_frame(c.fd, req, &frame_len);
      if (f == Frame::Partial) continue;
      if (f == Frame::Closed || f == Frame::Bad) {
        if (f == Frame::Bad) count(false, "malformed MBAP header");
        to_close.push_back(c.fd);
        continue;
      }
      modbus_set_socket(ctx_, c.fd);
      if (!own(req[6])) {  // gateway: the RTU side answers, in its own time
        std::vector<uint8_t> frame(req, req + frame_len);
        drain(c.fd, frame_len);
        c.waiting = true;
        const uint64_t id = c.id;
        if (!opt_.forwarder->submit(id, frame, [this](uint64_t conn, std::vector<uint8_t> r) { complete(conn, std::move(r)); })) {
          const auto busy = tcp_exception(frame, MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY);
          (void)!send(c.fd, busy.data(), busy.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
          c.waiting = false;
          count(false, "gateway busy");
        } else {
          count(true);
        }
        continue;
      }
      // MBAP delimits the frame, so a bad PDU is consumed whole and answered with
      // an exception; the connection stays in step.
      const bool known = supported_function(req[7]);
      if (!known || !well_formed(req, frame_len)) {
        drain(c.fd, frame_len);
        const int code = known ? MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE : MODBUS_EXCEPTION_ILLEGAL_FUNCTION;
        if (modbus_reply_exception(ctx_, req, code) < 0) to_close.push_back(c.fd);
        count(false, known ? "request length disagrees with its fields" : "illegal function " + std::to_string(req[7]));
        continue;
      }
      // The MBAP length delimits the frame (Modbus/TCP's framing rule), so one recv
      // takes it whole; libmodbus parses the PDU and builds the reply. modbus_receive
      // is not used here: it would block on a partial frame and cost two more
      // system calls per request (bench/modbus_bench.cpp).
      const int rc = int(recv(c.fd, req, size_t(frame_len), MSG_DONTWAIT));
      if (rc != frame_len) {
        count(false, std::string("receive: ") + modbus_strerror(errno));
        to_close.push_back(c.fd);
        continue;
      }
      if (handle_request(ctx_, plc_, req, rc, &opt_.writable) < 0) {
        count(false, std::string("reply: ") + modbus_strerror(errno));
        to_close.push_back(c.fd);
        continue;
      }
      count(true);
    }
    for (int fd : to_close) {
      close(fd);
      conns.erase(std::remove_if(conns.begin(), conns.end(), [fd](const Conn& c) { return c.fd == fd; }), conns.end());
    }
    if (pfds[1].revents & POLLIN) {
      const int fd = accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC | SOCK_NONBLOCK);
      if (fd >= 0) {
        if (int(conns.size()) >= opt_.max_connections) {
          close(fd);  // bounded: refuse rather than starve the ones we have
          count(false, "connection refused: " + std::to_string(opt_.max_connections) + " already open");
        } else {
          const int one = 1;
          setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
          conns.push_back({fd, next_id++, Clock::now()});
        }
      }
    }
    if (conns.size() != reported) {
      reported = conns.size();
      std::lock_guard<std::mutex> lk(mu_);
      st_.connections = reported;
    }
  }
  for (const auto& c : conns) close(c.fd);
}

}  // namespace modbus
}  // namespace plc_cell
