#include "plc_cell/io/transport.h"

#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "plc_cell/io/serial_line.h"

namespace plc_cell {
namespace {

constexpr int kMasterConnectMs = 3000;  // a master's connection attempt

class FdTransport : public Transport {
 public:
  void close() override {
    if (fd_ >= 0) ::close(fd_);
    fd_ = -1;
  }
  bool is_open() const override { return fd_ >= 0; }
  int fd() const override { return fd_; }
  void send(const std::string& b, int timeout_ms) override {
    if (fd_ < 0) open();
    if (!write_all(fd_, b.data(), b.size(), timeout_ms)) {
      close();
      throw ConnectionClosed(describe() + ": write failed");
    }
  }
  size_t recv(char* buf, size_t n, int timeout_ms) override {
    if (fd_ < 0) open();
    // The fd is non-blocking: try first, wait only when nothing is there yet.
    for (int pass = 0; pass < 2; ++pass) {
      const ssize_t r = ::read(fd_, buf, n);
      if (r > 0) return size_t(r);
      // A socket reads 0 at EOF; a tty with VMIN=0 reads 0 when it has nothing yet.
      const bool nothing = r == 0 ? !eof_on_zero_ : (errno == EAGAIN || errno == EWOULDBLOCK || errno == EINTR);
      if (!nothing) {
        close();
        throw ConnectionClosed(describe() + ": connection closed");
      }
      if (pass == 0 && !wait_readable(fd_, timeout_ms)) return 0;
    }
    return 0;
  }

 protected:
  int fd_ = -1;
  bool eof_on_zero_ = true;
};

class TcpTransport : public FdTransport {
 public:
  TcpTransport(std::string host, int port) : host_(host.empty() ? "127.0.0.1" : std::move(host)), port_(port) {}
  ~TcpTransport() override { close(); }
  void open() override {
    close();
    std::string why;
    const int fd = connect_tcp(host_, port_, kMasterConnectMs, &why);
    if (fd < 0) throw CommError(describe() + ": " + why);
    fd_ = fd;
  }
  std::string describe() const override { return "tcp " + host_ + ":" + std::to_string(port_); }

 private:
  std::string host_;
  int port_ = 0;
};

// The device is held by its path (io/serial_line.h): after a failed transaction the next
// one opens it again, so an adapter unplugged and plugged back is found.
class SerialTransport : public FdTransport {
 public:
  explicit SerialTransport(SerialSettings s) : line_(std::move(s)) { eof_on_zero_ = false; }
  ~SerialTransport() override { close(); }
  void open() override {
    close();
    if (!line_.open()) throw CommError(line_.last_error());
    fd_ = line_.fd();
  }
  void close() override {
    fd_ = -1;
    line_.close();
  }
  std::string describe() const override { return "serial " + line_.settings().to_string(); }
  void resynchronise(int quiet_ms) override {
    if (fd_ >= 0 && !drain_until_quiet(fd_, quiet_ms, 10 * quiet_ms)) {
      close();
      throw CommError(describe() + ": the line does not go quiet after a request that got no answer");
    }
  }

 private:
  SerialLine line_;
};

}  // namespace

std::unique_ptr<Transport> tcp_transport(const std::string& host_port) {
  std::string host;
  int port = 0;
  parse_host_port(host_port, &host, &port);
  return tcp_transport(host, port);
}
std::unique_ptr<Transport> tcp_transport(const std::string& host, int port) {
  return std::make_unique<TcpTransport>(host, port);
}
std::unique_ptr<Transport> serial_transport(const SerialSettings& line) {
  return std::make_unique<SerialTransport>(line);
}

int connect_tcp(const std::string& host_in, int port, int timeout_ms, std::string* error) {
  const std::string host = host_in.empty() ? "127.0.0.1" : host_in;
  addrinfo hints{}, *res = nullptr;
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res) != 0 || !res) {
    *error = "cannot resolve";
    return -1;
  }
  const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  int rc = ::connect(fd, res->ai_addr, res->ai_addrlen);
  int err = errno;
  freeaddrinfo(res);
  if (rc != 0 && err == EINPROGRESS) {
    pollfd p{fd, POLLOUT, 0};
    int r;
    while ((r = ::poll(&p, 1, timeout_ms)) < 0 && errno == EINTR) {
    }
    socklen_t len = sizeof err;
    if (r == 1 && ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &err, &len) == 0 && err == 0) rc = 0;
    else if (r == 0) err = ETIMEDOUT;
  }
  if (rc != 0) {
    ::close(fd);
    *error = std::string("cannot connect: ") + std::strerror(err);
    return -1;
  }
  int one = 1;
  setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
  return fd;
}

bool drain_until_quiet(int fd, int quiet_ms, int limit_ms) {
  using Clock = std::chrono::steady_clock;
  const auto end = Clock::now() + std::chrono::milliseconds(limit_ms);
  char buf[512];
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
    if (left <= 0) return false;
    if (!wait_readable(fd, int(std::min<int64_t>(quiet_ms, left)))) return left >= quiet_ms;  // quiet
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
    if (n == 0) {  // a socket at EOF (a tty with nothing reads 0 only when poll said so: hang-up)
      return false;
    }
  }
}

bool write_all(int fd, const char* buf, size_t n, int timeout_ms) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (n > 0) {
    const ssize_t w = ::write(fd, buf, n);
    if (w > 0) {
      buf += w;
      n -= size_t(w);
      continue;
    }
    if (w < 0 && errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLOUT, 0};
    ::poll(&p, 1, int(left));
  }
  return true;
}

bool wait_readable(int fd, int timeout_ms) {
  pollfd p{fd, POLLIN, 0};
  for (;;) {
    const int r = ::poll(&p, 1, timeout_ms);
    if (r < 0 && errno == EINTR) continue;
    return r > 0;
  }
}

}  // namespace plc_cell
