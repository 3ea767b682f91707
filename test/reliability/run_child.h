#pragma once
// `plc_cell run` as a child process that a test can kill -9. The port is read back from
// its "serving ... 127.0.0.1:PORT" log line (it binds port 0), so no sleeping and no guessing.
// Started and waited for through test/harness/child_process.h: default signal actions, and
// every wait bounded.
#include <signal.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <vector>

#include "../harness/child_process.h"

class RunChild {
 public:
  // Waits (up to timeout_ms) until every one of `servers` log lines appeared; servers = 0
  // returns as soon as the child is started (read its log with next_line()).
  // command: the tool's subcommand ("monitor" serves its page and logs the same way).
  explicit RunChild(const std::vector<std::string>& args, int servers = 1, int timeout_ms = 20000,
                    const char* command = "run")
      : proc_(argv(args, command)) {
    const bool up = proc_.read_until(
        [this, servers](const std::string& out) {
          ports.clear();
          for (size_t k = out.find("serving "); k != std::string::npos; k = out.find("serving ", k + 1)) {
            const auto h = out.find("127.0.0.1:", k);
            const auto eol = out.find('\n', k);
            if (h == std::string::npos || eol == std::string::npos || h > eol) continue;
            ports.push_back(std::stoi(out.substr(h + 10)));
          }
          return int(ports.size()) >= servers;
        },
        std::chrono::milliseconds(timeout_ms));
    if (!up) throw std::runtime_error(std::string("plc_cell ") + command + " did not start: " + log);
  }
  void kill9() { proc_.kill9(); }
  // Rest of the log after SIGTERM and exit.
  std::string terminate() {
    stop(SIGTERM);
    return log;
  }
  // The next whole line of the log (without '\n'); false on EOF or after timeout_ms.
  bool next_line(std::string* line, int timeout_ms = 20000) {
    return proc_.next_line(line, std::chrono::milliseconds(timeout_ms));
  }
  // Sends sig, reads the log to its end, reaps the child; returns its wait status. A child
  // still running kLimit after the signal is killed and the test fails saying so.
  int stop(int sig) { return proc_.stop(sig, kLimit, "its exit after signal " + std::to_string(sig)); }

  pid_t pid() const { return proc_.pid(); }
  std::vector<int> ports;

 private:
  static constexpr std::chrono::seconds kLimit{30};
  static std::vector<std::string> argv(const std::vector<std::string>& args, const char* command) {
    std::vector<std::string> av{PLC_CELL_TOOL, command};
    av.insert(av.end(), args.begin(), args.end());
    return av;
  }
  plc_cell::testing::ChildProcess proc_;

 public:
  const std::string& log = proc_.output();  // stdout and stderr so far
};
