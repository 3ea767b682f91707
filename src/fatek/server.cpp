#include "plc_cell/fatek/server.h"

#include <arpa/inet.h>
#include <fcntl.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/serial_port.h"
#include "plc_cell/io/connections.h"

namespace plc_cell {
namespace fatek {
namespace {

using Clock = std::chrono::steady_clock;

int64_t ms_since(Clock::time_point t) {
  return std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t).count();
}

void make_wake_pipe(int fds[2]) {
  if (::pipe2(fds, O_CLOEXEC | O_NONBLOCK) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
}

void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

void drain(int fd) {
  char buf[64];
  while (::read(fd, buf, sizeof buf) > 0) {
  }
}

// What the server keeps per connection (the time bounds are io/connections.h's).
struct Rx {
  Decoder decoder;
  std::string out;
};

}  // namespace

// ---- TCP -----------------------------------------------------------------------

TcpServer::TcpServer(Plc& plc, TcpServerOptions opt) : plc_(plc), opt_(std::move(opt)), slave_(plc, opt_.station) {
  slave_.set_writable(opt_.writable);
}

TcpServer::~TcpServer() { stop(); }

void TcpServer::start() {
  if (running_) return;
  addrinfo hints{}, *res = nullptr;
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE;
  const std::string host = opt_.host.empty() ? "127.0.0.1" : opt_.host;
  const std::string where = "FATEK TCP " + host + ":" + std::to_string(opt_.port);
  if (getaddrinfo(host.c_str(), std::to_string(opt_.port).c_str(), &hints, &res) != 0 || !res)
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
  make_wake_pipe(wake_);
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void TcpServer::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  close_fd(listen_fd_);
  close_fd(wake_[0]);
  close_fd(wake_[1]);
}

std::string TcpServer::describe() const {
  return "FATEK TCP " + (opt_.host.empty() ? std::string("127.0.0.1") : opt_.host) + ":" +
         std::to_string(bound_port_ ? bound_port_ : opt_.port) + " station " + std::to_string(opt_.station);
}

ServerStatus TcpServer::status() const {
  ServerStatus s;
  s.running = running_;
  s.requests = slave_.requests();
  s.rejected = slave_.rejected() + framing_errors_;
  s.connections = connections_;
  std::lock_guard<std::mutex> lk(err_mu_);
  s.last_error = last_error_;
  return s;
}

void TcpServer::loop() {
  Connections<Rx> conns(ConnectionLimits{opt_.max_connections, opt_.idle_timeout_ms, opt_.frame_timeout_ms});
  std::vector<pollfd> pfds;
  std::vector<int> dead;
  char buf[4096];
  auto note = [&](const std::string& e) {
    std::lock_guard<std::mutex> lk(err_mu_);
    last_error_ = e;
  };
  while (running_) {
    pfds.clear();
    pfds.push_back({wake_[0], POLLIN, 0});
    pfds.push_back({listen_fd_, POLLIN, 0});
    for (auto& c : conns.all()) pfds.push_back({c.fd, short(POLLIN | (c.x.out.empty() ? 0 : POLLOUT)), 0});
    ::poll(pfds.data(), pfds.size(), conns.poll_timeout_ms(Clock::now()));
    if (!running_) break;
    if (pfds[0].revents) drain(wake_[0]);
    dead.clear();
    const auto now = Clock::now();
    for (size_t i = 0; i < conns.size(); ++i) {
      auto& c = conns.all()[i];
      const short ev = pfds[i + 2].revents;
      if (ev & (POLLIN | POLLHUP | POLLERR)) {
        const ssize_t n = ::recv(c.fd, buf, sizeof buf, MSG_DONTWAIT);
        if (n == 0 || (n < 0 && errno != EAGAIN && errno != EINTR)) {
          dead.push_back(c.fd);
          continue;
        }
        if (n > 0) {
          c.x.decoder.feed(reinterpret_cast<const uint8_t*>(buf), size_t(n),
                           [&](const Frame& f) {
                             Connections<Rx>::complete(c, now);
                             slave_.handle(f, c.x.out);
                           },
                           [&](Decoder::Fault f) {
                             ++framing_errors_;
                             note(std::string("framing: ") + fault_name(f));
                           });
          // Bytes outside a frame (no STX yet) start no frame deadline: they are
          // dropped as they come, and only a complete request keeps the connection.
          if (c.x.decoder.in_frame()) Connections<Rx>::partial(c, now);
        }
      }
      if (!c.x.out.empty()) {
        const ssize_t w = ::send(c.fd, c.x.out.data(), c.x.out.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
        if (w > 0) c.x.out.erase(0, size_t(w));
        else if (w < 0 && errno != EAGAIN && errno != EINTR) {
          dead.push_back(c.fd);
          continue;
        }
        if (c.x.out.size() > opt_.max_pending_output) {
          note("client does not read its answers; dropped");
          dead.push_back(c.fd);
          continue;
        }
      }
      switch (conns.expired(c, now)) {
        case Connections<Rx>::Expiry::Frame:
          ++framing_errors_;
          note("framing: frame not complete within the frame timeout; connection closed");
          dead.push_back(c.fd);
          break;
        case Connections<Rx>::Expiry::Idle: dead.push_back(c.fd); break;
        case Connections<Rx>::Expiry::None: break;
      }
    }
    for (int fd : dead) {
      ::close(fd);
      conns.remove_fd(fd);
    }
    if (pfds[1].revents & POLLIN) {
      for (int k = 0; k < 16; ++k) {  // bounded: the clients we have are served in between
        const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_NONBLOCK | SOCK_CLOEXEC);
        if (fd < 0) break;
        int evicted = -1;
        const auto how = conns.admit(fd, Clock::now(), &evicted);
        if (how == Connections<Rx>::Admit::Refused) {
          ::close(fd);  // bounded: refuse beyond max_connections
          note("connection refused: limit reached");
          continue;
        }
        if (how == Connections<Rx>::Admit::Evicted) {
          ::close(evicted);
          note("connection closed for a new client: no complete request within the frame timeout");
        }
        int one = 1;
        setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof one);
      }
    }
    connections_ = conns.size();
  }
  for (auto& c : conns.all()) ::close(c.fd);
  connections_ = 0;
}

// ---- serial ----------------------------------------------------------------------

SerialServer::SerialServer(Plc& plc, SerialServerOptions opt)
    : plc_(plc), opt_(std::move(opt)), slave_(plc, opt_.station) {
  slave_.set_writable(opt_.writable);
}

SerialServer::~SerialServer() { stop(); }

void SerialServer::start() {
  if (running_) return;
  fd_ = open_serial_port(opt_.line);
  make_wake_pipe(wake_);
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void SerialServer::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  close_fd(fd_);
  close_fd(wake_[0]);
  close_fd(wake_[1]);
}

std::string SerialServer::describe() const {
  return "FATEK serial " + opt_.line.to_string() + " station " + std::to_string(opt_.station);
}

ServerStatus SerialServer::status() const {
  ServerStatus s;
  s.running = running_;
  s.requests = slave_.requests();
  s.rejected = slave_.rejected() + framing_errors_;
  s.link_up = link_up_;
  s.reopened = reopened_;
  std::lock_guard<std::mutex> lk(err_mu_);
  s.last_error = last_error_;
  return s;
}

// A device that went away (USB adapter unplugged, pty master closed) is reopened by
// path until it is back; meanwhile the server runs, link_up is false and says why.
bool SerialServer::wait_for_device() {
  while (running_) {
    try {
      fd_ = open_serial_port(opt_.line);
      link_up_ = true;
      ++reopened_;
      std::lock_guard<std::mutex> lk(err_mu_);
      last_error_ = "serial device back";
      return true;
    } catch (const Error&) {
      pollfd w{wake_[0], POLLIN, 0};
      ::poll(&w, 1, 200);  // retry period; stop() wakes us at once
    }
  }
  return false;
}

void SerialServer::loop() {
  Decoder dec;
  std::string out;
  char buf[1024];
  auto last_rx = Clock::now();
  auto note = [&](const std::string& e) {
    std::lock_guard<std::mutex> lk(err_mu_);
    last_error_ = e;
  };
  auto lost = [&](const std::string& why) {
    close_fd(fd_);
    fd_ = -1;
    link_up_ = false;
    dec = Decoder();
    note("serial device lost: " + why);
  };
  while (running_) {
    if (fd_ < 0 && !wait_for_device()) break;
    pollfd p[2] = {{wake_[0], POLLIN, 0}, {fd_, POLLIN, 0}};
    const int r = ::poll(p, 2, dec.in_frame() ? opt_.frame_timeout_ms : 200);
    if (!running_) break;
    if (r == 0 && dec.in_frame() && ms_since(last_rx) >= opt_.frame_timeout_ms) {
      dec.timeout();
      ++framing_errors_;
      note("framing: frame cut short by timeout");
      continue;
    }
    if (p[1].revents & (POLLHUP | POLLERR | POLLNVAL) && !(p[1].revents & POLLIN)) {
      // The other end of the line is gone (a pty's master closed, a device removed).
      lost(p[1].revents & POLLHUP ? "hang-up" : "I/O error");
      continue;
    }
    if (!(p[1].revents & POLLIN)) continue;
    const ssize_t n = ::read(fd_, buf, sizeof buf);
    if (n < 0 && errno != EAGAIN && errno != EINTR) {
      lost(std::strerror(errno));
      continue;
    }
    if (n == 0 && (p[1].revents & POLLHUP)) {  // a tty hang-up reads as end of file
      lost("hang-up");
      continue;
    }
    if (n <= 0) continue;
    last_rx = Clock::now();
    out.clear();
    dec.feed(reinterpret_cast<const uint8_t*>(buf), size_t(n), [&](const Frame& f) { slave_.handle(f, out); },
             [&](Decoder::Fault f) {
               ++framing_errors_;
               note(std::string("framing: ") + fault_name(f));
             });
    if (!out.empty() && !write_all(fd_, out.data(), out.size(), 2000)) note("serial write failed");
  }
}

std::unique_ptr<Server> make_tcp_server(Plc& plc, const std::string& host_port, int station,
                                        const ServerPolicy& policy) {
  TcpServerOptions o;
  parse_host_port(host_port, &o.host, &o.port);
  o.station = station;
  o.writable = policy.writable;
  if (policy.max_connections < 1) throw Error("FATEK TCP: max connections must be at least 1");
  if (policy.idle_timeout_ms < 1) throw Error("FATEK TCP: idle timeout must be positive");
  o.max_connections = policy.max_connections;
  o.idle_timeout_ms = policy.idle_timeout_ms;
  return std::make_unique<TcpServer>(plc, o);
}

std::unique_ptr<Server> make_serial_server(Plc& plc, const std::string& device_spec, int station,
                                           const ServerPolicy& policy) {
  SerialServerOptions o;
  o.writable = policy.writable;
  o.line = parse_serial_settings(device_spec, "7E1");
  o.station = station;
  return std::make_unique<SerialServer>(plc, o);
}

}  // namespace fatek

std::unique_ptr<Server> make_fatek_server(Plc& plc, const std::string& kind, const std::string& where, int station,
                                          const fatek::ServerPolicy& policy) {
  if (kind == "tcp") return fatek::make_tcp_server(plc, where, station, policy);
  if (kind == "serial") return fatek::make_serial_server(plc, where, station, policy);
  throw Error("FATEK server kind '" + kind + "' (expected tcp or serial)");
}

}  // namespace plc_cell
