#include "plc_cell/io/serial_listener.h"

#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/io/transport.h"
#include "close_fd.h"

namespace plc_cell {
namespace {

using Clock = std::chrono::steady_clock;

constexpr int kIdlePollMs = 200;     // how often a line with nothing buffered looks up
constexpr int kReplyTimeoutMs = 2000;  // a reply the line cannot take by then is dropped

}  // namespace

SerialListener::SerialListener(SerialProtocol& protocol, SerialSettings line, int frame_timeout_ms)
    : protocol_(protocol), line_(std::move(line)), frame_timeout_ms_(frame_timeout_ms) {}

SerialListener::~SerialListener() { stop(); }

void SerialListener::start() {
  if (running_) return;
  line_.open_or_throw();
  if (::pipe2(wake_, O_CLOEXEC | O_NONBLOCK) != 0) throw Error(std::string("pipe: ") + std::strerror(errno));
  running_ = true;
  thread_ = std::thread([this] { loop(); });
}

void SerialListener::stop() {
  if (!running_) return;
  running_ = false;
  (void)!::write(wake_[1], "x", 1);
  if (thread_.joinable()) thread_.join();
  line_.close();
  close_fd(wake_[0]);
  close_fd(wake_[1]);
}

std::string SerialListener::last_error() const {
  std::lock_guard<std::mutex> lk(err_mu_);
  return last_error_;
}

void SerialListener::note(const std::string& e) {
  std::lock_guard<std::mutex> lk(err_mu_);
  last_error_ = e;
}

bool SerialListener::wait_for_device() {
  while (running_) {
    if (line_.open()) {
      link_up_ = true;
      reopened_ = line_.reopened();
      note(line_.last_error());
      return true;
    }
    pollfd w{wake_[0], POLLIN, 0};
    ::poll(&w, 1, kIdlePollMs);  // the retry period; stop() wakes us at once
  }
  return false;
}

void SerialListener::lost(const std::string& why) {
  line_.lost(why);
  link_up_ = false;
  protocol_.drop_frame();
  note(line_.last_error());
}

void SerialListener::deliver(int fd, const uint8_t* data, size_t n) {
  std::string out, fault;
  protocol_.feed(data, n, out, fault);
  if (!fault.empty()) note(fault);
  if (!out.empty() && !write_all(fd, out.data(), out.size(), kReplyTimeoutMs)) note("serial write failed");
}

void SerialListener::loop() {
  char buf[1024];
  auto last_rx = Clock::now();
  while (running_) {
    if (!line_.is_open() && !wait_for_device()) break;
    const int fd = line_.fd();
    pollfd p[2] = {{wake_[0], POLLIN, 0}, {fd, POLLIN, 0}};
    const bool in_frame = protocol_.in_frame();
    const int wake = protocol_.wake_in_ms();
    int timeout = in_frame ? frame_timeout_ms_ : kIdlePollMs;
    if (wake >= 0) timeout = std::min(timeout, wake);
    const int r = ::poll(p, 2, timeout);
    if (!running_) break;
    if (r == 0 && wake >= 0) deliver(fd, nullptr, 0);  // the silence the protocol waited for
    const auto quiet_ms = std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - last_rx).count();
    if (r == 0 && protocol_.in_frame() && quiet_ms >= frame_timeout_ms_) {
      protocol_.drop_frame();
      ++frame_timeouts_;
      note("framing: frame cut short by timeout");
      continue;
    }
    if (p[1].revents & (POLLHUP | POLLERR | POLLNVAL) && !(p[1].revents & POLLIN)) {
      lost(p[1].revents & POLLHUP ? "hang-up" : "I/O error");  // the other end is gone
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
    deliver(fd, reinterpret_cast<const uint8_t*>(buf), size_t(n));
  }
}

}  // namespace plc_cell
