#pragma once
// Every process a test starts, started and waited for in one way.
//
// Two rules the suite keeps whatever environment starts it:
// - A child starts with the default action for SIGINT, SIGTERM, SIGQUIT, SIGHUP and SIGPIPE
//   and an empty signal mask. A shell that starts `make test &` ignores SIGINT, and an
//   ignored signal stays ignored across exec: a child signalled before it set up its own
//   stop handling would then never stop, and a test of the stop would wait forever.
// - Every wait has a bound. Past it the child is killed (SIGKILL, by its pid) and a
//   ChildTimeout says what was waited for, which gtest reports as the test's failure.
// A shell command leads a process group of its own, as coreutils' timeout makes one:
// whatever it starts (a pipeline) is killed with it. Other children stay in the test's
// group, so that a Ctrl-C at the terminal reaches them too.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

extern char** environ;

namespace plc_cell {
namespace testing {

class ChildTimeout : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class ChildProcess {
 public:
  using Clock = std::chrono::steady_clock;
  enum class Output { Captured, Discarded, Inherited };  // stdout and stderr, both
  enum class Group { Same, Own };                       // the test's process group, or its own

  // argv[0] is looked up on PATH when it has no '/'. Throws when it cannot be started.
  explicit ChildProcess(const std::vector<std::string>& argv, Output output = Output::Captured,
                        Group group = Group::Same)
      : own_group_(group == Group::Own) {
    int fds[2] = {-1, -1};
    if (output == Output::Captured && ::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error("pipe: " + errno_text());
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
    if (output == Output::Captured) {
      posix_spawn_file_actions_adddup2(&fa, fds[1], 1);
      posix_spawn_file_actions_adddup2(&fa, fds[1], 2);
    } else if (output == Output::Discarded) {
      posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
      posix_spawn_file_actions_adddup2(&fa, 1, 2);
    }
    posix_spawnattr_t attr;
    posix_spawnattr_init(&attr);
    sigset_t defaults, none;
    sigemptyset(&defaults);
    for (int s : {SIGINT, SIGTERM, SIGQUIT, SIGHUP, SIGPIPE}) sigaddset(&defaults, s);
    sigemptyset(&none);
    posix_spawnattr_setsigdefault(&attr, &defaults);
    posix_spawnattr_setsigmask(&attr, &none);
    posix_spawnattr_setpgroup(&attr, 0);
    posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGDEF | POSIX_SPAWN_SETSIGMASK |
                                        (own_group_ ? POSIX_SPAWN_SETPGROUP : 0));
    std::vector<char*> av;
    for (const auto& a : argv) av.push_back(const_cast<char*>(a.c_str()));
    av.push_back(nullptr);
    const int rc = argv.empty() ? EINVAL : ::posix_spawnp(&pid_, av[0], &fa, &attr, av.data(), environ);
    posix_spawnattr_destroy(&attr);
    posix_spawn_file_actions_destroy(&fa);
    if (output == Output::Captured) ::close(fds[1]);
    if (rc != 0) {
      if (fds[0] >= 0) ::close(fds[0]);
      pid_ = -1;
      throw std::runtime_error("cannot start " + (argv.empty() ? std::string("(nothing)") : argv[0]) + ": " +
                               errno_text(rc));
    }
    fd_ = fds[0];
    name_ = argv[0];
  }
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;
  ~ChildProcess() {
    kill9();
    if (fd_ >= 0) ::close(fd_);
  }

  pid_t pid() const { return pid_; }
  bool running() const { return pid_ > 0; }
  // Everything the child wrote so far (stdout and stderr, in order).
  const std::string& output() const { return out_; }

  // Reads until pred(output()) holds (true), or EOF or the bound (false).
  template <typename Pred, typename = std::enable_if_t<std::is_invocable_r_v<bool, Pred, const std::string&>>>
  bool read_until(Pred pred, std::chrono::milliseconds bound) {
    const auto end = Clock::now() + bound;
    while (!pred(out_)) {
      if (!read_some(end)) return false;
    }
    return true;
  }
  bool read_until(const std::string& needle, std::chrono::milliseconds bound) {
    return read_until([&needle](const std::string& s) { return s.find(needle) != std::string::npos; }, bound);
  }
  // The next whole line after the last one taken (without '\n'); false on EOF or the bound.
  bool next_line(std::string* line, std::chrono::milliseconds bound) {
    const auto end = Clock::now() + bound;
    for (;;) {
      const auto eol = out_.find('\n', cursor_);
      if (eol != std::string::npos) {
        *line = out_.substr(cursor_, eol - cursor_);
        cursor_ = eol + 1;
        return true;
      }
      if (!read_some(end)) return false;
    }
  }

  void signal(int sig) const {
    if (pid_ > 0) ::kill(pid_, sig);
  }
  // Reads the output to its end and reaps the child; returns its wait status. Past the
  // bound the child is killed and ChildTimeout names `what`.
  int wait(std::chrono::milliseconds bound, const std::string& what) {
    const auto end = Clock::now() + bound;
    while (fd_ >= 0) {
      if (!read_some(end)) {
        if (fd_ >= 0) timed_out(bound, what);  // the bound, not EOF
      }
    }
    for (;;) {
      int status = 0;
      const pid_t r = ::waitpid(pid_, &status, WNOHANG);
      if (r == pid_ || (r < 0 && errno == ECHILD)) {
        pid_ = -1;
        return status;
      }
      if (Clock::now() >= end) timed_out(bound, what);
      // The output is closed but the child has not exited yet: it is ending now.
      ::usleep(1000);
    }
  }
  // signal(sig), then wait().
  int stop(int sig, std::chrono::milliseconds bound, const std::string& what) {
    signal(sig);
    return wait(bound, what);
  }
  // For a destructor: sig, then SIGKILL if the child is still there after the bound.
  void end(int sig = SIGTERM, std::chrono::milliseconds bound = std::chrono::seconds(10)) noexcept {
    if (pid_ <= 0) return;
    try {
      stop(sig, bound, "its exit");
    } catch (...) {  // killed: nothing is left to wait for
    }
  }
  // The child (and its process group when it has one); SIGKILL cannot be caught, so the
  // wait ends.
  void kill9() {
    if (pid_ <= 0) return;
    if (own_group_) ::kill(-pid_, SIGKILL);
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }

 private:
  static std::string errno_text(int e = errno) { return std::to_string(e) + " (" + std::strerror(e) + ")"; }

  [[noreturn]] void timed_out(std::chrono::milliseconds bound, const std::string& what) {
    kill9();
    std::string tail = out_.size() > 2000 ? "..." + out_.substr(out_.size() - 2000) : out_;
    throw ChildTimeout(name_ + ": no end after " + std::to_string(bound.count()) + " ms waiting for " + what +
                       "; killed. Its output:\n" + tail);
  }
  // One read before `end`: false at the bound or EOF (then the pipe is closed).
  bool read_some(Clock::time_point end) {
    if (fd_ < 0) return false;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
    if (left <= 0) return false;
    pollfd pf{fd_, POLLIN, 0};
    const int n = ::poll(&pf, 1, int(left));
    if (n < 0 && errno == EINTR) return true;
    if (n <= 0) return false;
    char buf[4096];
    const ssize_t got = ::read(fd_, buf, sizeof buf);
    if (got < 0 && errno == EINTR) return true;
    if (got <= 0) {
      ::close(fd_);
      fd_ = -1;
      return false;
    }
    out_.append(buf, size_t(got));
    return true;
  }

  const bool own_group_;
  pid_t pid_ = -1;
  int fd_ = -1;
  std::string name_;
  std::string out_;
  size_t cursor_ = 0;
};

struct ToolResult {
  int status;       // exit status; -1 if it did not exit normally
  std::string out;  // stdout and stderr
};

// Runs argv to its end within limit_s seconds; past it the child is killed and the result
// says so (status -1, the reason last in out): a hung program fails its test.
inline ToolResult run_process(const std::vector<std::string>& argv, int limit_s = 60,
                              ChildProcess::Group group = ChildProcess::Group::Same) {
  ChildProcess c(argv, ChildProcess::Output::Captured, group);
  try {
    const int st = c.wait(std::chrono::seconds(limit_s), "its exit");
    return {WIFEXITED(st) ? WEXITSTATUS(st) : -1, c.output()};
  } catch (const ChildTimeout& e) {
    return {-1, c.output() + "\n" + e.what()};
  }
}

// A command line through sh, as a user types it (pipes, redirections).
inline ToolResult run_shell(const std::string& command, int limit_s = 60) {
  return run_process({"/bin/sh", "-c", command}, limit_s, ChildProcess::Group::Own);
}

}  // namespace testing
}  // namespace plc_cell
