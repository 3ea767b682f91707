#include "plc_cell/io/stop_signal.h"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {

StopSignal::StopSignal() {
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  // pthread_sigmask, not sigprocmask: the mask is per thread and this is the one that
  // every later thread copies.
  if (const int rc = pthread_sigmask(SIG_BLOCK, &set, nullptr)) throw Error(std::string("cannot block SIGINT/SIGTERM: ") + std::strerror(rc));
  fd_ = ::signalfd(-1, &set, SFD_CLOEXEC | SFD_NONBLOCK);
  if (fd_ < 0) throw Error(std::string("cannot open a signalfd: ") + std::strerror(errno));
}

StopSignal::~StopSignal() {
  if (fd_ >= 0) ::close(fd_);
}

bool StopSignal::wait_for(std::chrono::milliseconds timeout) {
  if (signo_) return true;
  pollfd p{fd_, POLLIN, 0};
  const int n = ::poll(&p, 1, int(timeout.count()));
  if (n <= 0) return false;  // timeout, or EINTR from a signal we do not handle: look again later
  signalfd_siginfo info;
  const ssize_t r = ::read(fd_, &info, sizeof info);
  if (r != ssize_t(sizeof info)) return false;
  signo_ = int(info.ssi_signo);
  return true;
}

bool StopSignal::wait_until_stopped(uint64_t duration_us) {
  const auto t0 = std::chrono::steady_clock::now();
  for (;;) {
    std::chrono::milliseconds wait(1000);
    if (duration_us) {
      const auto left = std::chrono::microseconds(duration_us) - (std::chrono::steady_clock::now() - t0);
      if (left <= left.zero()) return false;
      wait = std::min(wait, std::chrono::duration_cast<std::chrono::milliseconds>(left) + std::chrono::milliseconds(1));
    }
    if (wait_for(wait)) return true;
  }
}

const char* StopSignal::signal_name() const {
  switch (signo_) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}

}  // namespace plc_cell
