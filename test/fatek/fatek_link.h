#pragma once
// Test helpers: a raw TCP client that speaks bytes, and a socat pty pair.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "../harness/pty_pair.h"
#include "plc_cell/fatek/frame.h"
#include "plc_cell/fatek/serial_port.h"

namespace fatek_test {

inline int connect_local(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(uint16_t(port));
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0) throw std::runtime_error("connect");
  return fd;
}

// Sends bytes and waits (up to timeout_ms) for one frame; returns its encoded form or "".
inline std::string roundtrip(int fd, const std::string& bytes, int timeout_ms = 3000) {
  if (!bytes.empty() && ::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) != ssize_t(bytes.size())) return "";
  plc_cell::fatek::Decoder d;
  char buf[512];
  while (plc_cell::fatek::wait_readable(fd, timeout_ms)) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return "";
    for (ssize_t i = 0; i < n; ++i)
      if (d.push(uint8_t(buf[i])) == plc_cell::fatek::Decoder::Status::Frame) return encode_frame(d.frame());
  }
  return "";
}

// A fresh directory under /tmp, removed with its contents at the end of the scope.
class TempDir {
 public:
  TempDir() {
    char t[] = "/tmp/fatek_test_XXXXXX";
    if (!::mkdtemp(t)) throw std::runtime_error("mkdtemp");
    path = t;
  }
  ~TempDir() { (void)!std::system(("rm -rf '" + path + "'").c_str()); }
  std::string path;
};

// socat pty pair: a <-> b (dir/ttyA, dir/ttyB).
using plc_cell::testing::PtyPair;

}  // namespace fatek_test
