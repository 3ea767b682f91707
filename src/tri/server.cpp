#include "plc_cell/tri/server.h"

#include <cstdio>

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
  ServerStatus s;
  s.requests = slave_.requests();
  s.rejected = slave_.rejected();
  {
    std::lock_guard<std::mutex> lk(err_mu_);
    s.last_error = last_error_;
  }
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
    : opt_(std::move(opt)), slave_(plc, opt_.id), decoder_(opt_.wildcard_fcs),
      listener_(*this, std::move(line), opt_.frame_timeout_ms) {
  slave_.set_writable(opt_.writable);
}

SerialServer::~SerialServer() { stop(); }

void SerialServer::start() { listener_.start(); }

void SerialServer::stop() { listener_.stop(); }

std::string SerialServer::describe() const {
  return "TRi serial " + listener_.settings().to_string() + " ID " + id_text(slave_.id());
}

ServerStatus SerialServer::status() const {
  ServerStatus s;
  s.running = listener_.running();
  s.requests = slave_.requests();
  s.rejected = slave_.rejected() + listener_.frame_timeouts();
  s.link_up = listener_.link_up();
  s.reopened = listener_.reopened();
  s.last_error = listener_.last_error();
  return s;
}

void SerialServer::feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) {
  decoder_.feed(data, n, [&](const Decoder::Event& ev) {
    if (ev.kind == Decoder::Event::Error) fault = std::string("framing: ") + fault_name(ev.fault);
    slave_.handle(ev, out);
  });
}

}  // namespace tri
}  // namespace plc_cell
