#pragma once
// Test helpers: external processes (mbpoll, socat, libmodbus examples) with
// bounded waits on their I/O, never sleeps.
#include <poll.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <utility>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "../core/run_tool.h"

namespace plc_cell {
namespace test {

struct Output {
  int status = -1;
  std::string text;  // stdout + stderr
};

// Runs cmd through sh with a hard time limit (coreutils timeout).
inline Output run(const std::string& cmd, int limit_s = 60) {
  const testing::ToolResult r = testing::run_shell(cmd, limit_s);
  return {r.status, r.out};
}

inline std::string tmp_dir() {
  const std::string d = PLC_CELL_TEST_TMP;
  run("mkdir -p " + d);
  return d;
}

// A child process with its stderr on a pipe; killed (SIGTERM, by pid) on destruction.
class Child {
 public:
  explicit Child(const std::vector<std::string>& argv) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe");
    pid_ = fork();
    if (pid_ == 0) {
      dup2(fds[1], 2);
      dup2(fds[1], 1);
      close(fds[0]);
      std::vector<char*> a;
      for (const auto& s : argv) a.push_back(const_cast<char*>(s.c_str()));
      a.push_back(nullptr);
      execvp(a[0], a.data());
      _exit(127);
    }
    close(fds[1]);
    err_ = fds[0];
  }
  ~Child() {
    if (pid_ > 0) {
      kill(pid_, SIGTERM);
      waitpid(pid_, nullptr, 0);
    }
    if (err_ >= 0) close(err_);
  }
  // Reads output until it contains needle (true) or timeout_ms passes / EOF (false).
  bool wait_for(const std::string& needle, int timeout_ms = 10000) {
    const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
    while (seen_.find(needle) == std::string::npos) {
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
      if (left <= 0) return false;
      pollfd p{err_, POLLIN, 0};
      if (poll(&p, 1, int(left)) <= 0) return false;
      char buf[1024];
      const ssize_t n = read(err_, buf, sizeof buf);
      if (n <= 0) return false;
      seen_.append(buf, size_t(n));
    }
    return true;
  }
  const std::string& seen() const { return seen_; }
  pid_t pid() const { return pid_; }

 private:
  pid_t pid_ = -1;
  int err_ = -1;
  std::string seen_;
};

// A socat pty pair: a and b are symlinks to the two ends.
class PtyPair {
 public:
  explicit PtyPair(const std::string& name) {
    const std::string d = tmp_dir();
    a = d + "/" + name + "_a";
    b = d + "/" + name + "_b";
    socat_ = std::make_unique<Child>(std::vector<std::string>{
        "socat", "-d", "-d", "pty,raw,echo=0,link=" + a, "pty,raw,echo=0,link=" + b});
    if (!socat_->wait_for("starting data transfer loop"))
      throw std::runtime_error("socat did not start: " + socat_->seen());
  }
  std::string a, b;

 private:
  std::unique_ptr<Child> socat_;
};

// Compiles a libmodbus example (the .c may be gzipped) after literal text edits;
// each edit must apply, so a changed example fails loudly instead of testing nothing.
inline std::string build_example(const std::string& name,
                                 const std::vector<std::pair<std::string, std::string>>& edits,
                                 const std::string& tag) {
  const std::string dir = "/usr/share/doc/libmodbus-dev/examples/";
  const std::string d = tmp_dir();
  const std::string src = d + "/" + name + "_" + tag + ".c", bin = d + "/" + name + "_" + tag;
  for (const std::string& f : std::vector<std::string>{"unit-test.h", name + ".c"}) {
    struct stat st;
    const bool gz = stat((dir + f).c_str(), &st) != 0;
    const Output o = run((gz ? "zcat " + dir + f + ".gz" : "cat " + dir + f) + " > " + d + "/" + f + ".orig");
    if (o.status != 0) throw std::runtime_error("cannot read example " + f + ": " + o.text);
  }
  run("cp " + d + "/unit-test.h.orig " + d + "/unit-test.h");
  std::ifstream in(d + "/" + name + ".c.orig");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (const auto& e : edits) {
    const auto at = text.find(e.first);
    if (at == std::string::npos) throw std::runtime_error(name + ".c: cannot find '" + e.first + "'");
    text.replace(at, e.first.size(), e.second);
  }
  std::ofstream(src) << text;
  const Output o = run("cc -O2 -o " + bin + " " + src + " -I" + d + " $(pkg-config --cflags --libs libmodbus)", 120);
  if (o.status != 0) throw std::runtime_error("cannot build " + name + ": " + o.text);
  return bin;
}

}  // namespace test
}  // namespace plc_cell
