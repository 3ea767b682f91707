#include "plc_cell/fatek/server.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/serial_port.h"

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

// What the server keeps per connection besides its bytes: a decoder mid-frame.
struct Rx : TcpProtocol::Session {
  Decoder decoder;
};

TcpListenerOptions listener_options(const TcpServerOptions& o) {
  TcpListenerOptions l;
  l.name = "FATEK TCP";
  l.host = o.host;
  l.port = o.port;
  l.limits = ConnectionLimits{o.max_connections, o.idle_timeout_ms, o.frame_timeout_ms};
  l.max_input = 4096;  // the decoder takes every byte read
  l.max_pending_output = o.max_pending_output;
  return l;
}

}  // namespace

// ---- TCP -----------------------------------------------------------------------

TcpServer::TcpServer(Plc& plc, TcpServerOptions opt)
    : plc_(plc), opt_(std::move(opt)), slave_(plc, opt_.station), listener_(*this, listener_options(opt_)) {
  slave_.set_writable(opt_.writable);
}

TcpServer::~TcpServer() { stop(); }

void TcpServer::start() { listener_.start(); }

void TcpServer::stop() { listener_.stop(); }

std::string TcpServer::describe() const {
  return "FATEK TCP " + listener_.options().host + ":" + std::to_string(port() ? port() : opt_.port) + " station " +
         std::to_string(opt_.station);
}

ServerStatus TcpServer::status() const {
  ServerStatus s;
  s.running = listener_.running();
  s.requests = slave_.requests();
  s.rejected = slave_.rejected() + framing_errors_;
  s.connections = connections_;
  std::lock_guard<std::mutex> lk(err_mu_);
  s.last_error = last_error_;
  return s;
}

void TcpServer::note(const std::string& e) {
  std::lock_guard<std::mutex> lk(err_mu_);
  last_error_ = e;
}

std::unique_ptr<TcpProtocol::Session> TcpServer::open() { return std::make_unique<Rx>(); }

TcpProtocol::Taken TcpServer::take(uint64_t, Session* session, std::string& in, std::string& out) {
  Decoder& dec = static_cast<Rx*>(session)->decoder;
  Taken t;
  dec.feed(reinterpret_cast<const uint8_t*>(in.data()), in.size(),
           [&](const Frame& f) {
             ++t.requests;
             slave_.handle(f, out);
           },
           [&](Decoder::Fault f) {
             ++framing_errors_;
             note(std::string("framing: ") + fault_name(f));
           });
  in.clear();
  // Bytes outside a frame (no STX yet) start no frame deadline: they are dropped as
  // they come, and only a complete request keeps the connection.
  t.partial = dec.in_frame();
  return t;
}

void TcpServer::on_event(Event e, int) {
  switch (e) {
    case Event::Refused: note("connection refused: limit reached"); break;
    case Event::Evicted:
      note("connection closed for a new client: no complete request within the frame timeout");
      break;
    case Event::FrameTimeout:
      ++framing_errors_;
      note("framing: frame not complete within the frame timeout; connection closed");
      break;
    case Event::SlowReader: note("client does not read its answers; dropped"); break;
    case Event::ClosedMidRequest:
    case Event::ReplyFailed: break;
  }
}

// ---- serial ----------------------------------------------------------------------

SerialServer::SerialServer(Plc& plc, SerialServerOptions opt)
    : plc_(plc), opt_(std::move(opt)), slave_(plc, opt_.station), line_(opt_.line) {
  slave_.set_writable(opt_.writable);
}

SerialServer::~SerialServer() { stop(); }

void SerialServer::start() {
  if (running_) return;
  line_.open_or_throw();
  make_wake_pipe(wake_);
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void SerialServer::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  line_.close();
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
    if (line_.open()) {
      link_up_ = true;
      reopened_ = line_.reopened();
      std::lock_guard<std::mutex> lk(err_mu_);
      last_error_ = line_.last_error();
      return true;
    }
    pollfd w{wake_[0], POLLIN, 0};
    ::poll(&w, 1, 200);  // retry period; stop() wakes us at once
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
    line_.lost(why);
    link_up_ = false;
    dec = Decoder();
    note(line_.last_error());
  };
  while (running_) {
    if (!line_.is_open() && !wait_for_device()) break;
    const int fd = line_.fd();
    pollfd p[2] = {{wake_[0], POLLIN, 0}, {fd, POLLIN, 0}};
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
    const ssize_t n = ::read(fd, buf, sizeof buf);
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
    if (!out.empty() && !write_all(fd, out.data(), out.size(), 2000)) note("serial write failed");
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

}  // namespace plc_cell
