#include "plc_cell/io/serial_line.h"

#include <fcntl.h>
#include <termios.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

speed_t speed_of(int baud) {
  switch (baud) {
    case 4800: return B4800;
    case 9600: return B9600;
    case 19200: return B19200;
    case 38400: return B38400;
    case 57600: return B57600;
    case 115200: return B115200;
    case 230400: return B230400;
    case 460800: return B460800;
    case 500000: return B500000;
    case 576000: return B576000;
    case 921600: return B921600;
    default: return B0;
  }
}

bool is_pty(const std::string& device) {
  char buf[PATH_MAX];
  if (!::realpath(device.c_str(), buf)) return false;
  return std::strncmp(buf, "/dev/pts/", 9) == 0;
}

}  // namespace

bool serial_baud_supported(int baud) { return speed_of(baud) != B0; }

int open_serial_line(const SerialSettings& s) {
  const std::string name = s.to_string();
  if (!serial_baud_supported(s.baud))
    throw Error("serial " + name + ": baud " + std::to_string(s.baud) +
                " not supported (4800, 9600, 19200, 38400, 57600, 115200, 230400, 460800, 921600)");
  if (s.data_bits != 7 && s.data_bits != 8) throw Error("serial " + name + ": data bits must be 7 or 8");
  const int fd = ::open(s.device.c_str(), O_RDWR | O_NOCTTY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) throw Error("serial " + name + ": cannot open: " + std::strerror(errno));
  termios t{};
  if (tcgetattr(fd, &t) != 0) {
    const int err = errno;
    ::close(fd);
    throw Error("serial " + name + ": not a serial line: " + std::strerror(err));
  }
  cfmakeraw(&t);
  t.c_cflag &= ~tcflag_t(CSIZE | PARENB | PARODD | CSTOPB | CRTSCTS);
  t.c_cflag |= CLOCAL | CREAD | (s.data_bits == 7 ? CS7 : CS8);
  if (s.parity == 'E') t.c_cflag |= PARENB;
  if (s.parity == 'O') t.c_cflag |= PARENB | PARODD;
  if (s.stop_bits == 2) t.c_cflag |= CSTOPB;
  t.c_iflag &= ~tcflag_t(IXON | IXOFF | IXANY | INPCK | ISTRIP);
  t.c_cc[VMIN] = 0;
  t.c_cc[VTIME] = 0;
  cfsetispeed(&t, speed_of(s.baud));
  cfsetospeed(&t, speed_of(s.baud));
  bool ok = tcsetattr(fd, TCSANOW, &t) == 0;
  if (!ok && is_pty(s.device)) {
    // Linux ptys refuse some data-bit/parity changes (EINVAL), depending on their state.
    // A pty carries bytes unchanged and FATEK is 7-bit ASCII, so 8N1 there is byte-for-byte
    // what 7E1 is on a real line; all that matters is raw mode without echo.
    t.c_cflag &= ~tcflag_t(CSIZE | PARENB | PARODD | CSTOPB);
    t.c_cflag |= CS8;
    ok = tcsetattr(fd, TCSANOW, &t) == 0;
    termios now{};
    if (!ok && tcgetattr(fd, &now) == 0 && !(now.c_lflag & (ICANON | ECHO)) && !(now.c_oflag & OPOST)) ok = true;
  }
  if (!ok) {
    const int err = errno;
    ::close(fd);
    throw Error("serial " + name + ": cannot configure: " + std::strerror(err));
  }
  tcflush(fd, TCIOFLUSH);
  return fd;
}

bool SerialLine::open() {
  if (fd_ >= 0) return true;
  try {
    fd_ = open_serial_line(s_);
  } catch (const Error& e) {
    last_error_ = e.what();
    return false;
  }
  if (was_lost_) {
    was_lost_ = false;
    ++reopened_;
    last_error_ = "serial device back";
  }
  return true;
}

void SerialLine::open_or_throw() {
  if (!open()) throw Error(last_error_);
}

void SerialLine::lost(const std::string& why) {
  close();
  was_lost_ = true;
  last_error_ = "serial device lost: " + why;
}

void SerialLine::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

}  // namespace plc_cell
