#include "plc_cell/tri/server.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace tri {
namespace {

// What a connection keeps besides its bytes: a decoder mid-frame.
struct Rx : TcpProtocol::Session {
  explicit Rx(bool wildcard) : decoder(wildcard) {}
  Decoder decoder;
};

TcpListenerOptions listener_options(const std::string& host, int port, const ServerOptions& o) {
  TcpListenerOptions l;
  l.name = "TRi TCP";
  l.host = host;
  l.port = port;
  l.limits = ConnectionLimits{o.max_connections, o.idle_timeout_ms, o.frame_timeout_ms};
  l.max_input = 4096;  // the decoder takes every byte read
  l.max_pending_output = 64 * 1024;
  return l;
}

std::string id_text(int id) {
  char s[8];
  std::snprintf(s, sizeof s, "%02X", unsigned(id & 0xFF));
  return s;
}

ServerStatus slave_status(const Slave& slave, std::mutex& mu, const std::string& last_error) {
  ServerStatus s;
  s.requests = slave.requests();
  s.rejected = slave.rejected();
  std::lock_guard<std::mutex> lk(mu);
  s.last_error = last_error;
  return s;
}

// Writes all of buf to a serial line within timeout_ms.
bool send_all(int fd, const std::string& buf, int timeout_ms) {
  size_t done = 0;
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  while (done < buf.size()) {
    const ssize_t n = ::write(fd, buf.data() + done, buf.size() - done);
    if (n > 0) {
      done += size_t(n);
      continue;
    }
    if (n < 0 && errno != EAGAIN && errno != EINTR) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    pollfd p{fd, POLLOUT, 0};
    ::poll(&p, 1, int(left.count()));
  }
  return true;
}

}  // namespace

// ---- TCP -------------------------------------------------------------------------

TcpServer::TcpServer(Plc& plc, std::string host, int port, ServerOptions opt)
    : opt_(std::move(opt)), slave_(plc, opt_.id), listener_(*this, listener_options(host, port, opt_)) {
  slave_.set_writable(opt_.writable);
}

TcpServer::~TcpServer() { stop(); }
void TcpServer::start() { listener_.start(); }
void TcpServer::stop() { listener_.stop(); }

std::string TcpServer::describe() const {
  return "TRi TCP " + listener_.options().host + ":" + std::to_string(port() ? port() : listener_.options().port) +
         " ID " + id_text(slave_.id());
}

ServerStatus TcpServer::status() const {
  ServerStatus s = slave_status(slave_, err_mu_, last_error_);
  s.running = listener_.running();
  s.connections = connections_;
  return s;
}

void TcpServer::note(const std::string& e) {
  std::lock_guard<std::mutex> lk(err_mu_);
  last_error_ = e;
}

std::unique_ptr<TcpProtocol::Session> TcpServer::open() { return std::make_unique<Rx>(opt_.wildcard_fcs); }

TcpProtocol::Taken TcpServer::take(uint64_t, Session* session, std::string& in, std::string& out) {
  Decoder& dec = static_cast<Rx*>(session)->decoder;
  Taken t;
  dec.feed(in, [&](const Decoder::Event& ev) {
    if (ev.kind == Decoder::Event::FrameReady) ++t.requests;
    if (ev.kind == Decoder::Event::Error) note(std::string("framing: ") + fault_name(ev.fault));
    slave_.handle(ev, out);
  });
  in.clear();
  t.partial = dec.in_frame();
  return t;
}

void TcpServer::on_event(Event e, int) {
  switch (e) {
    case Event::Refused: note("connection refused: limit reached"); break;
    case Event::Evicted: note("connection closed for a new client: no complete request within the frame timeout"); break;
    case Event::FrameTimeout: note("framing: frame not complete within the frame timeout; connection closed"); break;
    case Event::SlowReader: note("client does not read its answers; dropped"); break;
    case Event::ClosedMidRequest:
    case Event::ReplyFailed: break;
  }
}

// ---- serial ----------------------------------------------------------------------

SerialServer::SerialServer(Plc& plc, SerialSettings line, ServerOptions opt)
    : opt_(std::move(opt)), slave_(plc, opt_.id), line_(std::move(line)) {
  slave_.set_writable(opt_.writable);
}

SerialServer::~SerialServer() { stop(); }

void SerialServer::start() {
  if (running_) return;
  line_.open_or_throw();
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void SerialServer::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  line_.close();
  for (int& fd : wake_) {
    ::close(fd);
    fd = -1;
  }
}

std::string SerialServer::describe() const {
  return "TRi serial " + line_.settings().to_string() + " ID " + id_text(slave_.id());
}

ServerStatus SerialServer::status() const {
  ServerStatus s = slave_status(slave_, err_mu_, last_error_);
  s.running = running_;
  s.link_up = link_up_;
  return s;
}

void SerialServer::note(const std::string& e) {
  std::lock_guard<std::mutex> lk(err_mu_);
  last_error_ = e;
}

void SerialServer::loop() {
  Decoder dec(opt_.wildcard_fcs);
  std::string out;
  char buf[512];
  while (running_) {
    if (!line_.is_open()) {
      if (!line_.open()) {  // the device went away: retry until it is back or we stop
        pollfd w{wake_[0], POLLIN, 0};
        ::poll(&w, 1, 200);
        continue;
      }
      link_up_ = true;
    }
    pollfd p[2] = {{wake_[0], POLLIN, 0}, {line_.fd(), POLLIN, 0}};
    const int r = ::poll(p, 2, dec.in_frame() ? opt_.frame_timeout_ms : 200);
    if (!running_) break;
    if (r == 0) {
      if (dec.in_frame()) note("framing: frame cut short by timeout");
      dec.reset();  // a frame not whole within the timeout is dropped
      continue;
    }
    const bool hup = p[1].revents & (POLLHUP | POLLERR | POLLNVAL);
    ssize_t n = (p[1].revents & POLLIN) ? ::read(line_.fd(), buf, sizeof buf) : 0;
    if ((n < 0 && errno != EAGAIN && errno != EINTR) || (n <= 0 && hup)) {
      line_.lost(hup ? "hang-up" : std::strerror(errno));
      link_up_ = false;
      dec.reset();
      note(line_.last_error());
      continue;
    }
    if (n <= 0) continue;
    out.clear();
    dec.feed(reinterpret_cast<const uint8_t*>(buf), size_t(n), [&](const Decoder::Event& ev) {
      if (ev.kind == Decoder::Event::Error) note(std::string("framing: ") + fault_name(ev.fault));
      slave_.handle(ev, out);
    });
    if (!out.empty() && !send_all(line_.fd(), out, 2000)) note("serial write failed");
  }
}

}  // namespace tri
}  // namespace plc_cell
