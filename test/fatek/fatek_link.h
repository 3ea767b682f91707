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

// socat pty pair: a <-> b. Started in the constructor, killed in the destructor.
class PtyPair {
 public:
  explicit PtyPair(const std::string& dir) {
    a = dir + "/ttyA";
    b = dir + "/ttyB";
    int err_pipe[2];
    if (::pipe(err_pipe) != 0) throw std::runtime_error("pipe");
    pid_ = ::fork();
    if (pid_ == 0) {
      ::dup2(err_pipe[1], 2);
      ::close(err_pipe[0]);
      ::execlp("socat", "socat", "-d", "-d", ("pty,raw,echo=0,link=" + a).c_str(),
               ("pty,raw,echo=0,link=" + b).c_str(), static_cast<char*>(nullptr));
      _exit(127);
    }
    ::close(err_pipe[1]);
    // Block until socat reports that both ptys exist (its -d -d log), no sleeping.
    std::string log;
    char c;
    while (log.find("starting data transfer loop") == std::string::npos && ::read(err_pipe[0], &c, 1) == 1)
      log.push_back(c);
    err_fd_ = err_pipe[0];
    if (log.find("starting data transfer loop") == std::string::npos)
      throw std::runtime_error("socat did not start: " + log);
  }
  ~PtyPair() {
    if (pid_ > 0) {
      ::kill(pid_, SIGTERM);
      ::waitpid(pid_, nullptr, 0);
    }
    if (err_fd_ >= 0) ::close(err_fd_);
  }
  std::string a, b;

 private:
  pid_t pid_ = -1;
  int err_fd_ = -1;
};

}  // namespace fatek_test
