#pragma once
// `plc_cell run` as a child process that a test can kill -9. The port is read back from
// its "serving ... 127.0.0.1:PORT" log line (it binds port 0), so no sleeping and no guessing.
#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <stdexcept>
#include <string>
#include <vector>

class RunChild {
 public:
  // Waits (up to timeout_ms) until every one of `servers` log lines appeared; servers = 0
  // returns as soon as the child is forked (read its log with next_line()).
  // command: the tool's subcommand ("monitor" serves its page and logs the same way).
  explicit RunChild(const std::vector<std::string>& args, int servers = 1, int timeout_ms = 20000,
                    const char* command = "run") {
    int p[2];
    if (::pipe2(p, O_CLOEXEC) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(p[1], 2);
      std::vector<char*> av{const_cast<char*>(PLC_CELL_TOOL), const_cast<char*>(command)};
      for (const auto& a : args) av.push_back(const_cast<char*>(a.c_str()));
      av.push_back(nullptr);
      ::execv(PLC_CELL_TOOL, av.data());
      _exit(127);
    }
    ::close(p[1]);
    fd_ = p[0];
    while (int(ports.size()) < servers) {
      pollfd pf{fd_, POLLIN, 0};
      if (::poll(&pf, 1, timeout_ms) <= 0) throw std::runtime_error("plc_cell run did not start: " + log);
      char buf[512];
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n <= 0) throw std::runtime_error("plc_cell run exited: " + log);
      log.append(buf, size_t(n));
      ports.clear();
      for (size_t k = log.find("serving "); k != std::string::npos; k = log.find("serving ", k + 1)) {
        const auto h = log.find("127.0.0.1:", k);
        const auto eol = log.find('\n', k);
        if (h == std::string::npos || eol == std::string::npos || h > eol) continue;
        ports.push_back(std::stoi(log.substr(h + 10)));
      }
    }
  }
  ~RunChild() {
    if (pid_ > 0) {
      ::kill(pid_, SIGKILL);
      ::waitpid(pid_, nullptr, 0);
    }
    ::close(fd_);
  }
  void kill9() {
    ::kill(pid_, SIGKILL);
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
  }
  // Rest of the log after SIGTERM and exit (blocks until the child closed stderr).
  std::string terminate() {
    ::kill(pid_, SIGTERM);
    char buf[512];
    ssize_t n;
    while ((n = ::read(fd_, buf, sizeof buf)) > 0) log.append(buf, size_t(n));
    ::waitpid(pid_, nullptr, 0);
    pid_ = -1;
    return log;
  }

  // The next whole line of the log (without '\n'); false on EOF or after timeout_ms.
  bool next_line(std::string* line, int timeout_ms = 20000) {
    for (;;) {
      const auto eol = log.find('\n', cursor_);
      if (eol != std::string::npos) {
        *line = log.substr(cursor_, eol - cursor_);
        cursor_ = eol + 1;
        return true;
      }
      pollfd pf{fd_, POLLIN, 0};
      if (::poll(&pf, 1, timeout_ms) <= 0) return false;
      char buf[512];
      const ssize_t n = ::read(fd_, buf, sizeof buf);
      if (n <= 0) return false;
      log.append(buf, size_t(n));
    }
  }
  // Sends sig, reads the log to its end, reaps the child; returns its wait status.
  int stop(int sig) {
    ::kill(pid_, sig);
    char buf[512];
    ssize_t n;
    while ((n = ::read(fd_, buf, sizeof buf)) > 0) log.append(buf, size_t(n));
    int status = 0;
    ::waitpid(pid_, &status, 0);
    pid_ = -1;
    return status;
  }

  pid_t pid() const { return pid_; }
  std::vector<int> ports;
  std::string log;

 private:
  pid_t pid_ = -1;
  int fd_ = -1;
  size_t cursor_ = 0;  // next_line() reads from here
};
