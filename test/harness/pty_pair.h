#pragma once
// A socat pty pair, a <-> b: two linked serial devices for a serial master and slave of a
// test. Started in the constructor, which returns once socat reports both ends (its -d -d
// log), and stopped in the destructor.
#include <chrono>
#include <stdexcept>
#include <string>

#include "child_process.h"

namespace plc_cell {
namespace testing {

class PtyPair {
 public:
  // a and b are the links `<dir>/<prefix>A` and `<dir>/<prefix>B`.
  explicit PtyPair(const std::string& dir, const std::string& prefix = "tty")
      : a(dir + "/" + prefix + "A"),
        b(dir + "/" + prefix + "B"),
        socat_({"socat", "-d", "-d", "pty,raw,echo=0,link=" + a, "pty,raw,echo=0,link=" + b}) {
    if (!socat_.read_until("starting data transfer loop", std::chrono::seconds(10)))
      throw std::runtime_error("socat did not start: " + socat_.output());
  }
  ~PtyPair() { socat_.end(); }
  PtyPair(const PtyPair&) = delete;
  PtyPair& operator=(const PtyPair&) = delete;

  const std::string a, b;

 private:
  ChildProcess socat_;
};

}  // namespace testing
}  // namespace plc_cell
