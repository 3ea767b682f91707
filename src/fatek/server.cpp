#include "plc_cell/fatek/server.h"

#include "plc_cell/core/error.h"
#include "plc_cell/fatek/serial_port.h"

namespace plc_cell {
namespace fatek {
namespace {

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
    : opt_(std::move(opt)), slave_(plc, opt_.station), listener_(*this, opt_.line, opt_.frame_timeout_ms) {
  slave_.set_writable(opt_.writable);
}

SerialServer::~SerialServer() { stop(); }

void SerialServer::start() { listener_.start(); }

void SerialServer::stop() { listener_.stop(); }

std::string SerialServer::describe() const {
  return "FATEK serial " + opt_.line.to_string() + " station " + std::to_string(opt_.station);
}

ServerStatus SerialServer::status() const {
  ServerStatus s;
  s.running = listener_.running();
  s.requests = slave_.requests();
  s.rejected = slave_.rejected() + framing_errors_ + listener_.frame_timeouts();
  s.link_up = listener_.link_up();
  s.reopened = listener_.reopened();
  s.last_error = listener_.last_error();
  return s;
}

void SerialServer::feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) {
  decoder_.feed(data, n, [&](const Frame& f) { slave_.handle(f, out); },
                [&](Decoder::Fault f) {
                  ++framing_errors_;
                  fault = std::string("framing: ") + fault_name(f);
                });
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
