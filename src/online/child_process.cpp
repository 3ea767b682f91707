#include "plc_cell/online/child_process.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>

extern char** environ;

namespace plc_cell {
namespace online {

namespace {

constexpr size_t kMaxErr = 64 * 1024;
constexpr size_t kMaxOut = 16 * 1024 * 1024;

bool executable(const std::string& p) { return !p.empty() && access(p.c_str(), X_OK) == 0; }

// Reads what the two pipes have until both close or the deadline passes.
bool drain(int out_fd, int err_fd, std::chrono::steady_clock::time_point deadline, ChildResult* r) {
  pollfd fds[2] = {{out_fd, POLLIN, 0}, {err_fd, POLLIN, 0}};
  char buf[8192];
  while (fds[0].fd >= 0 || fds[1].fd >= 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) return false;
    const int n = poll(fds, 2, static_cast<int>(std::min<int64_t>(left.count(), 1000)));
    if (n < 0 && errno != EINTR) return false;
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      const ssize_t got = read(fds[i].fd, buf, sizeof buf);
      if (got <= 0) {
        fds[i].fd = -1;
        continue;
      }
      std::string& to = i == 0 ? r->out : r->err;
      if (to.size() < (i == 0 ? kMaxOut : kMaxErr)) to.append(buf, static_cast<size_t>(got));
    }
  }
  return true;
}

}  // namespace

ChildResult run_child(const std::vector<std::string>& argv, uint64_t timeout_us) {
  ChildResult r;
  if (argv.empty() || !executable(argv[0])) {
    r.failure = "cannot run " + (argv.empty() ? std::string("nothing") : argv[0]);
    return r;
  }
  int out[2], err[2];
  if (pipe2(out, O_CLOEXEC) != 0) {
    r.failure = std::string("pipe: ") + std::strerror(errno);
    return r;
  }
  if (pipe2(err, O_CLOEXEC) != 0) {
    r.failure = std::string("pipe: ") + std::strerror(errno);
    close(out[0]);
    close(out[1]);
    return r;
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  std::vector<char*> args;
  for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, argv[0].c_str(), &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(out[1]);
  close(err[1]);
  if (rc != 0) {
    r.failure = "cannot start " + argv[0] + ": " + std::strerror(rc);
    close(out[0]);
    close(err[0]);
    return r;
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::microseconds(timeout_us);
  if (!drain(out[0], err[0], deadline, &r)) {
    r.timed_out = true;
    kill(pid, SIGKILL);
  }
  close(out[0]);
  close(err[0]);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (!r.timed_out && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  return r;
}

std::string tool_path() {
  char self[4096];
  const ssize_t n = readlink("/proc/self/exe", self, sizeof self - 1);
  if (n > 0) {
    std::string dir(self, static_cast<size_t>(n));
    dir = dir.substr(0, dir.rfind('/') + 1);
    if (executable(dir + "plc_cell")) return dir + "plc_cell";
  }
  if (const char* env = std::getenv("PLC_CELL_TOOL"); env && executable(env)) return env;
  return "";
}

}  // namespace online
}  // namespace plc_cell
