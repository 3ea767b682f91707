#include "plc_cell/modbus/tcp_server.h"

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

// A frame in the first `have` bytes: its length, 0 if not all there yet, -1 for a
// header no Modbus/TCP peer sends (the stream cannot be resynchronised: close).
int frame_length(const uint8_t* b, int have) {
  if (have < 6) return 0;
  const int proto = b[2] << 8 | b[3], length = b[4] << 8 | b[5];
  if (proto != 0 || length < 2 || length > MODBUS_TCP_MAX_ADU_LENGTH - 6) return -1;
  return have >= 6 + length ? 6 + length : 0;
}

TcpListenerOptions listener_options(const TcpServerOptions& o) {
  TcpListenerOptions l;
  l.name = "Modbus TCP";
  l.host = o.host;
  l.port = o.port;
  l.limits = ConnectionLimits{o.max_connections, o.idle_timeout_ms, o.frame_timeout_ms};
  // At most one whole request is buffered: a larger header is refused before.
  l.max_input = MODBUS_TCP_MAX_ADU_LENGTH;
  // A reply goes out with one non-blocking send: a client that leaves its replies
  // unread until its socket buffer is full is closed, not waited for.
  l.max_pending_output = 0;
  return l;
}

}  // namespace

TcpServer::TcpServer(Plc& plc, TcpServerOptions opt)
    : plc_(plc), opt_(std::move(opt)), listener_(*this, listener_options(opt_)) {}

TcpServer::~TcpServer() { stop(); }

void TcpServer::start() { listener_.start(); }

void TcpServer::stop() { listener_.stop(); }

std::string TcpServer::describe() const {
  return "Modbus TCP " + listener_.options().host + ":" + std::to_string(bound_port() ? bound_port() : opt_.port);
}

ServerStatus TcpServer::status() const {
  std::lock_guard<std::mutex> lk(mu_);
  ServerStatus s = st_;
  s.running = listener_.running();
  return s;
}

void TcpServer::count(bool ok, const std::string& err) {
  std::lock_guard<std::mutex> lk(mu_);
  (ok ? st_.requests : st_.rejected)++;
  if (!err.empty()) st_.last_error = err;
}

void TcpServer::on_connections(size_t open) {
  std::lock_guard<std::mutex> lk(mu_);
  st_.connections = open;
}

// One request per call: its reply goes out before the next is executed, so a client
// that stops reading has no further request of its pipeline applied.
TcpProtocol::Taken TcpServer::take(uint64_t conn, Session*, std::string& in, std::string& out) {
  Taken t;
  const uint8_t* f = reinterpret_cast<const uint8_t*>(in.data());
  const int flen = frame_length(f, int(in.size()));
  if (flen < 0) {
    count(false, "malformed MBAP header");
    t.bad = true;
    return t;
  }
  if (flen > 0) {
    t.requests = 1;
    if (opt_.forwarder && f[6] != opt_.own_unit && f[6] != 0 && f[6] != 255) {
      // gateway: the RTU side answers, in its own time
      std::vector<uint8_t> frame(f, f + flen);
      if (opt_.forwarder->submit(conn, frame, [this](uint64_t c, std::vector<uint8_t> r) {
            listener_.deliver(c, std::string(r.begin(), r.end()));
          })) {
        t.waiting = true;
        count(true);
      } else {
        const auto busy = tcp_exception(frame, MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY);
        out.append(busy.begin(), busy.end());
        count(false, "gateway busy");
      }
    } else {
      // MBAP delimits the frame, so a bad PDU is consumed whole and answered with an
      // exception; the connection stays in step. The PDU is decoded with no lock held.
      uint8_t rsp[MODBUS_TCP_MAX_ADU_LENGTH];
      const PduAnswer a = answer_pdu(plc_, f + 7, flen - 7, rsp + 7, &opt_.writable, *opt_.map);
      std::memcpy(rsp, f, 7);
      rsp[2] = rsp[3] = 0;
      rsp[4] = uint8_t((a.length + 1) >> 8);
      rsp[5] = uint8_t(a.length + 1);
      out.append(reinterpret_cast<const char*>(rsp), size_t(7 + a.length));
      if (a.accepted) count(true);
      else if (a.exception == MODBUS_EXCEPTION_ILLEGAL_FUNCTION) count(false, "illegal function " + std::to_string(f[7]));
      else count(false, "exception " + std::to_string(a.exception) + " to function " + std::to_string(f[7]));
    }
    in.erase(0, size_t(flen));
  }
  t.partial = !in.empty();
  return t;
}

void TcpServer::on_event(Event e, int err) {
  switch (e) {
    case Event::Refused:
      count(false, "connection refused: " + std::to_string(opt_.max_connections) + " already open");
      break;
    case Event::Evicted:
      count(false, "connection closed for a new client: no complete request within the frame timeout");
      break;
    case Event::FrameTimeout: count(false, "request not complete within the frame timeout"); break;
    case Event::ClosedMidRequest: count(false, "connection closed in the middle of a request"); break;
    case Event::ReplyFailed:
    case Event::SlowReader: count(false, std::string("reply: ") + strerror(err)); break;
  }
}

}  // namespace modbus
}  // namespace plc_cell
