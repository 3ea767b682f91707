#pragma once
// A termios serial line (or pty) in raw mode, and small fd helpers with timeouts.
#include <cstddef>
#include <cstdint>
#include <string>

#include "plc_cell/io/serial_settings.h"

namespace plc_cell {
namespace fatek {

// Opens and configures the line (4800..921600 baud, 7/8 data bits, N/E/O parity, 1/2 stop).
// Returns a non-blocking fd; throws plc_cell::Error naming the device on failure.
int open_serial_port(const SerialSettings& s);
bool baud_supported(int baud);

// Writes all of buf, waiting at most timeout_ms overall. Returns false on error or timeout.
bool write_all(int fd, const char* buf, size_t n, int timeout_ms);
// Waits up to timeout_ms for fd to become readable (true) or for wake_fd (-1: none).
bool wait_readable(int fd, int timeout_ms);

}  // namespace fatek
}  // namespace plc_cell
