#include "plc_cell/core/unreadable.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace plc_cell {

std::string why_unreadable(const std::string& path) {
  std::string why;
  const int fd = path.empty() ? -1 : ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st;
  if (path.empty()) why = "no path given";
  else if (fd < 0) why = std::strerror(errno);
  else if (::fstat(fd, &st) == 0 && S_ISDIR(st.st_mode)) why = "it is a directory";
  if (fd >= 0) ::close(fd);
  if (why.empty() || path.empty()) return why;
  std::error_code ec;
  const std::filesystem::path abs = std::filesystem::absolute(path, ec).lexically_normal();
  return why + " (looked for " + (ec ? path : abs.string()) + ")";
}

}  // namespace plc_cell
