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
#include "../harness/pty_pair.h"

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

// A child process with its output on a pipe; stopped (SIGTERM, SIGKILL past 10 s) on
// destruction.
class Child : public testing::ChildProcess {
 public:
  using ChildProcess::ChildProcess;
  ~Child() { end(); }
  // Reads output until it contains needle (true) or timeout_ms passes / EOF (false).
  bool wait_for(const std::string& needle, int timeout_ms = 10000) {
    return read_until(needle, std::chrono::milliseconds(timeout_ms));
  }
  const std::string& seen() const { return output(); }
};

// A socat pty pair: a and b are symlinks to the two ends, under tmp_dir().
class PtyPair : public testing::PtyPair {
 public:
  explicit PtyPair(const std::string& name) : testing::PtyPair(tmp_dir(), name + "_") {}
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
