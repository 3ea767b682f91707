#include "plc_cell/modbus/rtu_server.h"

#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/modbus/slave_handler.h"

namespace plc_cell {
namespace modbus {

RtuServer::RtuServer(Plc& plc, SerialSettings port, int slave_id, WritableRanges writable, const MapProfile& map)
    : plc_(plc),
      port_(std::move(port)),
      id_(slave_id),
      writable_(std::move(writable)),
      map_(map),
      framer_(t35_us(port_.baud), int64_t(frame_timeout_ms_) * 1000) {
  if (id_ < 1 || id_ > 247) throw Error("Modbus RTU slave id " + std::to_string(id_) + " outside 1..247");
}

RtuServer::~RtuServer() { stop(); }

void RtuServer::start() {
  if (listener_ && listener_->running()) return;
  // Over a pty relay the bytes of one frame can come apart by more than t3.5, so a frame
  // whose CRC does not hold yet is given until the frame timeout to complete.
  framer_ = RtuFramer(t35_us(port_.baud), int64_t(frame_timeout_ms_) * 1000);
  garbage_seen_ = 0;
  listener_ = std::make_unique<SerialListener>(static_cast<SerialProtocol&>(*this), port_, frame_timeout_ms_);
  try {
    listener_->start();
  } catch (const Error& e) {
    listener_.reset();
    throw Error("Modbus RTU " + port_.to_string() + ": " + e.what());
  }
}

void RtuServer::stop() {
  if (listener_) listener_->stop();
}

std::string RtuServer::describe() const {
  return "Modbus RTU " + port_.to_string() + " slave " + std::to_string(id_);
}

ServerStatus RtuServer::status() const {
  ServerStatus s;
  if (listener_) {
    s.running = listener_->running();
    s.link_up = listener_->link_up();
    s.reopened = listener_->reopened();
    s.last_error = listener_->last_error();
  }
  std::lock_guard<std::mutex> lk(mu_);
  s.requests = requests_;
  s.rejected = rejected_;
  return s;
}

int64_t RtuServer::now_us() const {
  return int64_t(std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0_).count());
}

int RtuServer::wake_in_ms() const {
  const int64_t now = now_us();
  const int64_t dl = framer_.deadline_us(now);
  return dl < 0 ? -1 : int(std::max<int64_t>(0, (dl - now + 999) / 1000));
}

// On the listener's thread: bytes in (none when the silence wake_in_ms() asked for came),
// every frame they complete answered into out.
void RtuServer::feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) {
  if (n > 0) framer_.feed(data, n, now_us());
  for (;;) {
    const RtuFramer::Event ev = framer_.poll(now_us());
    if (framer_.garbage_bytes() != garbage_seen_) {
      garbage_seen_ = framer_.garbage_bytes();
      std::lock_guard<std::mutex> lk(mu_);
      ++rejected_;
      fault = "line noise or a frame with a bad CRC dropped";
    }
    if (ev == RtuFramer::Event::None) break;
    if (ev == RtuFramer::Event::Frame) answer(framer_.frame(), out, fault);
  }
}

void RtuServer::answer(const std::vector<uint8_t>& f, std::string& out, std::string& fault) {
  const uint8_t slave = f[0];
  if (slave != id_ && slave != 0) return;  // another slave's frame, or its reply
  uint8_t rsp[kMaxPdu];
  const PduAnswer a = answer_pdu(plc_, f.data() + 1, int(f.size()) - 3, rsp, &writable_, map_);
  if (slave != 0 && a.length > 0) {  // a broadcast is executed, never answered
    uint8_t adu[kMaxPdu + 3];
    const int n = rtu_adu(slave, rsp, a.length, adu);
    out.append(reinterpret_cast<const char*>(adu), size_t(n));
  }
  std::lock_guard<std::mutex> lk(mu_);
  ++(a.accepted ? requests_ : rejected_);
  if (!a.accepted) fault = "exception " + std::to_string(a.exception) + " to function " + std::to_string(f[1]);
}

}  // namespace modbus
}  // namespace plc_cell
