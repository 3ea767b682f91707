#pragma once
// Internal to the io layer: the listeners close their descriptors through this, so a
// descriptor is closed once and then reads as closed (-1).
#include <unistd.h>

namespace plc_cell {

inline void close_fd(int& fd) {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

}  // namespace plc_cell
