#pragma once
// Small fd helpers with timeouts for the FATEK lines (serial or TCP). The serial device
// itself is opened by io/serial_line.h.
#include <cstddef>
#include <cstdint>
#include <string>

namespace plc_cell {
namespace fatek {

// Writes all of buf, waiting at most timeout_ms overall. Returns false on error or timeout.
bool write_all(int fd, const char* buf, size_t n, int timeout_ms);
// Waits up to timeout_ms for fd to become readable (true) or for wake_fd (-1: none).
bool wait_readable(int fd, int timeout_ms);

}  // namespace fatek
}  // namespace plc_cell
