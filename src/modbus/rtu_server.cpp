#include "plc_cell/modbus/rtu_server.h"

#include <cerrno>
#include <chrono>
#include <string>

#include <cerrno>

#include <modbus/modbus.h>

#include "plc_cell/core/error.h"
#include "plc_cell/modbus/slave_handler.h"

namespace plc_cell {
namespace modbus {

RtuServer::RtuServer(Plc& plc, SerialSettings port, int slave_id, WritableRanges writable)
    : plc_(plc), port_(std::move(port)), id_(slave_id), writable_(std::move(writable)) {
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
  // Wake up now and then to notice stop(); a frame in progress is unaffected.
  modbus_set_indication_timeout(ctx_, 0, 200000);
  // After a request for another slave, libmodbus 3.1.6 reads the next frame as that
  // slave's reply and drops it, waiting up to the response timeout. Were the other
  // slave silent, a master's next request to us would be eaten. A master waits out
  // its own timeout (100 ms and more) before that next request, so a short window
  // keeps both cases right; a reply later than 50 ms is dropped as a bad request.
  modbus_set_response_timeout(ctx_, 0, 50000);
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
  uint8_t req[MODBUS_RTU_MAX_ADU_LENGTH];
  while (!stop_) {
    const int rc = modbus_receive(ctx_, req);
    if (rc == 0) continue;  // for another slave
    if (rc < 0) {
      if (errno == ETIMEDOUT || errno == EINTR) continue;
      if (errno < MODBUS_ENOBASE) {  // an OS error, not a bad frame: the device is gone
        reopen(modbus_strerror(errno));
        continue;
      }
      std::lock_guard<std::mutex> lk(mu_);
      st_.rejected++;
      st_.last_error = modbus_strerror(errno);
      modbus_flush(ctx_);
      continue;
    }
    const bool ok = supported_function(req[1]);
    const int r = handle_request(ctx_, plc_, req, rc, &writable_);
    std::lock_guard<std::mutex> lk(mu_);
    (ok && r >= 0 ? st_.requests : st_.rejected)++;
    if (r < 0) st_.last_error = modbus_strerror(errno);
  }
}

}  // namespace modbus
}  // namespace plc_cell
