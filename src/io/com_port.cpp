#include "plc_cell/io/com_port.h"

#include "plc_cell/io/transport.h"

#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace plc_cell {
namespace {

constexpr int kPortConnectMs = 1000;

}  // namespace

std::string ComLine::to_string() const { return is_tcp() ? "tcp:" + tcp : serial.to_string(); }

ComPort::ComPort(int number, ComLine line)
    : number_(number), line_(std::move(line)), has_line_(true), serial_(line_.serial) {
  (void)fd();
  thread_ = std::thread([this] { run(); });
}

ComPort::ComPort(int number) : number_(number), has_line_(false), serial_(SerialSettings{}) {
  thread_ = std::thread([this] { run(); });
}

ComPort::~ComPort() {
  {
    std::lock_guard<std::mutex> lk(mu_);
    stop_ = true;
    jobs_.clear();
  }
  cv_.notify_all();
  thread_.join();
  if (tcp_fd_ >= 0) ::close(tcp_fd_);
}

void ComPort::submit(std::function<void()> job) {
  {
    std::lock_guard<std::mutex> lk(mu_);
    if (stop_) return;
    jobs_.push_back(std::move(job));
  }
  cv_.notify_all();
}

void ComPort::run() {
  std::unique_lock<std::mutex> lk(mu_);
  for (;;) {
    cv_.wait(lk, [&] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    std::function<void()> job = std::move(jobs_.front());
    jobs_.pop_front();
    lk.unlock();
    job();
    lk.lock();
  }
}

int ComPort::open_tcp() {
  std::string host;
  int port = 0;
  try {
    parse_host_port(line_.tcp, &host, &port);
  } catch (const std::exception& e) {
    std::lock_guard<std::mutex> lk(mu_);
    error_ = e.what();
    return -1;
  }
  std::string why;
  const int fd = connect_tcp(host, port, kPortConnectMs, &why);
  if (fd < 0) {
    std::lock_guard<std::mutex> lk(mu_);
    error_ = "tcp " + line_.tcp + ": " + why;
  }
  return fd;
}

int ComPort::fd() {
  if (!has_line_) return -1;
  if (line_.is_tcp()) {
    if (tcp_fd_ < 0) {
      tcp_fd_ = open_tcp();
      if (tcp_fd_ >= 0 && tcp_lost_) {
        tcp_lost_ = false;
        std::lock_guard<std::mutex> lk(mu_);
        ++reopened_;
        error_ = "connection back";
      }
    }
    up_ = tcp_fd_ >= 0;
    return tcp_fd_;
  }
  const bool ok = serial_.open();
  up_ = ok;
  std::lock_guard<std::mutex> lk(mu_);
  error_ = serial_.last_error();
  reopened_ = serial_.reopened();
  return ok ? serial_.fd() : -1;
}

void ComPort::lost(const std::string& why) {
  up_ = false;
  if (line_.is_tcp()) {
    if (tcp_fd_ >= 0) ::close(tcp_fd_);
    tcp_fd_ = -1;
    tcp_lost_ = true;
    std::lock_guard<std::mutex> lk(mu_);
    error_ = "connection lost: " + why;
    return;
  }
  serial_.lost(why);
  std::lock_guard<std::mutex> lk(mu_);
  error_ = serial_.last_error();
}

void ComPort::resynchronise(int quiet_ms) {
  if (!is_open()) return;
  if (line_.is_tcp()) return lost("closed after a request that got no answer: a late one may follow");
  if (!drain_until_quiet(serial_.fd(), quiet_ms, 10 * quiet_ms)) lost("the line does not go quiet after a request that got no answer");
}

std::string ComPort::last_error() const {
  std::lock_guard<std::mutex> lk(mu_);
  return error_;
}

uint64_t ComPort::reopened() const {
  std::lock_guard<std::mutex> lk(mu_);
  return reopened_;
}

}  // namespace plc_cell
