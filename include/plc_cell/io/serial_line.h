#pragma once
// A serial device held by its path, so that a line which went away (USB adapter
// unplugged, pty master closed, tty hang-up) comes back when the device does: every
// owner of a hand-opened serial line (the FATEK serial server, the COM ports of
// FUN150/151) reopens through this one class instead of each keeping its own fd logic.
// Lines libmodbus opens itself (modbus_connect) are not held here.
#include <cstdint>
#include <string>

#include "plc_cell/io/serial_settings.h"

namespace plc_cell {

// Opens and configures the line (4800..921600 baud, 7/8 data bits, N/E/O parity, 1/2 stop)
// in raw mode. Returns a non-blocking fd; throws plc_cell::Error naming the device.
int open_serial_line(const SerialSettings& s);
bool serial_baud_supported(int baud);

class SerialLine {
 public:
  explicit SerialLine(SerialSettings s) : s_(std::move(s)) {}
  ~SerialLine() { close(); }
  SerialLine(const SerialLine&) = delete;
  SerialLine& operator=(const SerialLine&) = delete;

  // Opens the device unless it is open; false (and last_error() says why) when it is not
  // there. A success after lost() counts as a reopen.
  bool open();
  // Throws plc_cell::Error when the device cannot be opened (the first open of a server).
  void open_or_throw();
  // The line is dead (read error, hang-up): closed now, reopened by the next open().
  void lost(const std::string& why);
  void close();

  int fd() const { return fd_; }
  bool is_open() const { return fd_ >= 0; }
  uint64_t reopened() const { return reopened_; }
  const std::string& last_error() const { return last_error_; }
  const SerialSettings& settings() const { return s_; }

 private:
  SerialSettings s_;
  int fd_ = -1;
  bool was_lost_ = false;
  uint64_t reopened_ = 0;
  std::string last_error_;
};

}  // namespace plc_cell
