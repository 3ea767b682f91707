#include "plc_cell/io/stop_signal.h"

#include <poll.h>
#include <signal.h>
#include <sys/signalfd.h>
#include <unistd.h>

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

const char* StopSignal::signal_name() const {
  switch (signo_) {
    case SIGINT: return "SIGINT";
    case SIGTERM: return "SIGTERM";
    default: return "";
  }
}

}  // namespace plc_cell
