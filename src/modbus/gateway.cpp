#include "plc_cell/modbus/gateway.h"

#include <cerrno>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace modbus {

using Clock = std::chrono::steady_clock;

RtuForwarder::RtuForwarder(const GatewayOptions& o) : opt_(o) {}

RtuForwarder::~RtuForwarder() { stop(); }

void RtuForwarder::start() {
  if (port_) return;
  const SerialSettings& s = opt_.line;
  ctx_ = modbus_new_rtu(s.device.c_str(), s.baud, s.parity, s.data_bits, s.stop_bits);
  if (!ctx_) throw Error("gateway line " + s.to_string() + ": " + modbus_strerror(errno));
  modbus_set_response_timeout(ctx_, uint32_t(opt_.wait_ms / 1000), uint32_t(opt_.wait_ms % 1000) * 1000);
  ComLine line;
  line.serial = s;
  port_ = std::make_unique<ComPort>(0, line);  // tries the line now
  if (!port_->line_up()) {
    const std::string why = port_->last_error();
    port_.reset();
    modbus_free(ctx_);
    ctx_ = nullptr;
    throw Error("gateway line " + s.to_string() + ": " + why);
  }
  std::lock_guard<std::mutex> lk(mu_);
  stop_ = false;
}

void RtuForwarder::stop() {
  if (!port_) return;
  std::deque<Job> left;
  {
    std::lock_guard<std::mutex> lk(mu_);
    stop_ = true;
    left.swap(jobs_);
  }
  port_.reset();  // waits for the transaction on the line
  for (auto& j : left) j.done(j.conn, tcp_exception(j.frame, MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY));
  modbus_free(ctx_);
  ctx_ = nullptr;
}

bool RtuForwarder::submit(uint64_t conn, std::vector<uint8_t> frame, Done done) {
  std::lock_guard<std::mutex> lk(mu_);
  if (stop_ || jobs_.size() + (busy_ ? 1 : 0) >= opt_.max_pending) return false;
  jobs_.push_back({conn, std::move(frame), std::move(done), Clock::now()});
  port_->submit([this] { run_next(); });
  return true;
}

uint64_t RtuForwarder::no_response() const {
  std::lock_guard<std::mutex> lk(mu_);
  return no_response_;
}

// One attempt on the line: true with the reply's RTU frame, false when none came.
bool RtuForwarder::attempt(int fd, const std::vector<uint8_t>& f, std::vector<uint8_t>* reply) {
  const uint8_t unit = f[6], fc = f[7];
  modbus_set_socket(ctx_, fd);
  modbus_flush(ctx_);
  if (modbus_send_raw_request(ctx_, f.data() + 6, int(f.size() - 6)) < 0) {
    port_->lost(modbus_strerror(errno));  // the line itself failed: reopened by the next attempt
    return false;
  }
  // receive_confirmation checks CRC and slave id, and sizes the reply by its own
  // function code (an exception reply included).
  uint8_t rsp[MODBUS_RTU_MAX_ADU_LENGTH];
  const int n = modbus_receive_confirmation(ctx_, rsp);
  if (n < 4 || rsp[0] != unit || (rsp[1] & 0x7F) != fc) return false;
  reply->assign(rsp, rsp + n);
  return true;
}

// One request on the line: up to 1 + retries attempts of `wait` each.
std::vector<uint8_t> RtuForwarder::transact(const std::vector<uint8_t>& f) {
  const uint8_t unit = f[6];
  modbus_set_slave(ctx_, unit);
  std::vector<uint8_t> rsp;
  for (int n = 0; n <= opt_.retries; ++n) {
    const int fd = port_->fd();
    if (fd < 0 || !attempt(fd, f, &rsp)) continue;
    const int pdu = int(rsp.size()) - 1 - 2;  // minus slave id and CRC
    std::vector<uint8_t> out = {f[0], f[1], 0, 0, uint8_t((pdu + 1) >> 8), uint8_t(pdu + 1), unit};
    out.insert(out.end(), rsp.begin() + 1, rsp.begin() + 1 + pdu);
    return out;
  }
  std::lock_guard<std::mutex> lk(mu_);
  no_response_++;
  return tcp_exception(f, MODBUS_EXCEPTION_GATEWAY_TARGET);
}

// On the port's thread, once per submitted request, in order.
void RtuForwarder::run_next() {
  Job j;
  {
    std::lock_guard<std::mutex> lk(mu_);
    if (stop_ || jobs_.empty()) return;
    j = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
  }
  std::vector<uint8_t> reply;
  if (Clock::now() - j.queued > std::chrono::milliseconds(opt_.busy_ms))
    reply = tcp_exception(j.frame, MODBUS_EXCEPTION_SLAVE_OR_SERVER_BUSY);  // waited too long for the line
  else
    reply = transact(j.frame);
  j.done(j.conn, std::move(reply));
  std::lock_guard<std::mutex> lk(mu_);
  busy_ = false;
}

GatewayServer::GatewayServer(Plc& plc, GatewayOptions o) : opt_(std::move(o)) {
  if (opt_.tcp.own_unit < 1 || opt_.tcp.own_unit > 247) throw Error("gateway: own unit id must be 1..247");
  if (opt_.wait_ms < 1 || opt_.retries < 0 || opt_.max_pending < 1) throw Error("gateway: wait, retries or queue out of range");
  rtu_ = std::make_unique<RtuForwarder>(opt_);
  TcpServerOptions t = opt_.tcp;
  t.forwarder = rtu_.get();
  tcp_ = std::make_unique<TcpServer>(plc, t);
}

void GatewayServer::start() {
  rtu_->start();
  tcp_->start();
}

// The line first: its last replies still reach a running TCP server.
void GatewayServer::stop() {
  rtu_->stop();
  tcp_->stop();
}

std::string GatewayServer::describe() const {
  return "Modbus gateway TCP " + opt_.tcp.host + ":" + std::to_string(tcp_->bound_port()) + " unit " +
         std::to_string(opt_.tcp.own_unit) + " -> RTU " + opt_.line.to_string() + " (wait " +
         std::to_string(opt_.wait_ms) + " ms, " + std::to_string(opt_.retries) + " retries)";
}

ServerStatus GatewayServer::status() const {
  ServerStatus s = tcp_->status();
  const uint64_t nr = rtu_->no_response();
  if (nr) s.last_error = std::to_string(nr) + " forwarded requests without reply (0B)";
  return s;
}

}  // namespace modbus
}  // namespace plc_cell
