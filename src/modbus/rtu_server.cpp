#include "plc_cell/modbus/rtu_server.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"
#include "plc_cell/modbus/rtu_frame.h"
#include "plc_cell/modbus/slave_handler.h"

namespace plc_cell {
namespace modbus {

RtuServer::RtuServer(Plc& plc, SerialSettings port, int slave_id, WritableRanges writable, MapProfile map)
    : plc_(plc), port_(std::move(port)), id_(slave_id), writable_(std::move(writable)), map_(map) {
  if (id_ < 1 || id_ > 247) throw Error("Modbus RTU slave id " + std::to_string(id_) + " outside 1..247");
}

RtuServer::~RtuServer() { stop(); }

void RtuServer::start() {
  if (thread_.joinable()) return;
  const std::string what = "Modbus RTU " + port_.to_string();
  ctx_ = modbus_new_rtu(port_.device.c_str(), port_.baud, port_.parity, port_.data_bits, port_.stop_bits);
  if (!ctx_) throw Error(what + ": " + modbus_strerror(errno));
  modbus_set_slave(ctx_, id_);
  if (modbus_connect(ctx_) < 0) {
    const std::string why = modbus_strerror(errno);
    modbus_free(ctx_);
    ctx_ = nullptr;
    throw Error(what + ": cannot open: " + why);
  }
  stop_ = false;
  {
    std::lock_guard<std::mutex> lk(mu_);
    st_.running = true;
  }
  thread_ = std::thread([this] { run(); });
}

void RtuServer::stop() {
  if (!thread_.joinable()) return;
  stop_ = true;
  thread_.join();
  modbus_close(ctx_);
  modbus_free(ctx_);
  ctx_ = nullptr;
  std::lock_guard<std::mutex> lk(mu_);
  st_.running = false;
}

std::string RtuServer::describe() const {
  return "Modbus RTU " + port_.to_string() + " slave " + std::to_string(id_);
}

ServerStatus RtuServer::status() const {
  std::lock_guard<std::mutex> lk(mu_);
  return st_;
}

// A device that went away (USB adapter unplugged, pty master closed) is reopened by path
// every 200 ms until it is back; meanwhile link_up is false and last_error says why.
void RtuServer::reopen(const std::string& why) {
  modbus_close(ctx_);
  {
    std::lock_guard<std::mutex> lk(mu_);
    st_.link_up = false;
    st_.last_error = "serial device lost: " + why;
  }
  while (!stop_) {
    if (modbus_connect(ctx_) == 0) {
      std::lock_guard<std::mutex> lk(mu_);
      st_.link_up = true;
      st_.reopened++;
      st_.last_error = "serial device back";
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // retry period, not a test wait
  }
}

void RtuServer::run() {
  // Frames are cut by our own framer (modbus/rtu_frame.h: libmodbus cannot frame
  // function codes it does not implement). Over a pty relay bytes of one frame can
  // come apart by more than t3.5, so a frame whose CRC does not hold yet is given
  // until the frame timeout to complete.
  const auto t0 = std::chrono::steady_clock::now();
  const auto now_us = [&] {
    return int64_t(std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - t0).count());
  };
  RtuFramer framer(t35_us(port_.baud), int64_t(frame_timeout_ms_) * 1000);
  uint8_t buf[512];
  uint8_t rsp[MODBUS_RTU_MAX_ADU_LENGTH];
  uint8_t out[MODBUS_RTU_MAX_ADU_LENGTH + 2];
  size_t garbage_seen = 0;
  while (!stop_) {
    const int fd = modbus_get_socket(ctx_);
    const int64_t now = now_us();
    const int64_t dl = framer.deadline_us(now);
    const int timeout = dl < 0 ? 200 : int(std::max<int64_t>(0, (dl - now + 999) / 1000));
    pollfd p{fd, POLLIN, 0};
    const int r = ::poll(&p, 1, timeout);
    if (r < 0 && errno != EINTR) {
      reopen(strerror(errno));
      framer.reset();
      continue;
    }
    if (r > 0) {
      const ssize_t n = ::read(fd, buf, sizeof buf);
      if (n < 0 && errno != EAGAIN && errno != EINTR) {
        reopen(strerror(errno));
        framer.reset();
        continue;
      }
      if (n == 0 && (p.revents & POLLHUP)) {  // a tty hang-up reads as end of file
        reopen("hang-up");
        framer.reset();
        continue;
      }
      if (n > 0) framer.feed(buf, size_t(n), now_us());
    }
    for (;;) {
      const RtuFramer::Event ev = framer.poll(now_us());
      if (framer.garbage_bytes() != garbage_seen) {
        garbage_seen = framer.garbage_bytes();
        std::lock_guard<std::mutex> lk(mu_);
        st_.rejected++;
        st_.last_error = "line noise or a frame with a bad CRC dropped";
      }
      if (ev != RtuFramer::Event::Frame) {
        if (ev == RtuFramer::Event::None) break;
        continue;
      }
      const std::vector<uint8_t>& f = framer.frame();
      const uint8_t slave = f[0];
      if (slave != id_ && slave != 0) continue;  // another slave's frame, or its reply
      const PduAnswer a = answer_pdu(plc_, f.data() + 1, int(f.size()) - 3, rsp, &writable_, map_);
      bool sent = true;
      if (slave != 0 && a.length > 0) {  // a broadcast is executed, never answered
        const int n = rtu_adu(slave, rsp, a.length, out);
        sent = ::write(fd, out, size_t(n)) == n;
      }
      std::lock_guard<std::mutex> lk(mu_);
      (a.accepted && sent ? st_.requests : st_.rejected)++;
      if (!sent) st_.last_error = std::string("serial write: ") + strerror(errno);
      else if (!a.accepted) st_.last_error = "exception " + std::to_string(a.exception) + " to function " + std::to_string(f[1]);
    }
  }
}

}  // namespace modbus
}  // namespace plc_cell
