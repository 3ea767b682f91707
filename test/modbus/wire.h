#pragma once
// Raw Modbus requests on a socket or a pty for tests: bytes in, bytes out, bounded
// waits (poll with a deadline), never sleeps.
#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/modbus/rtu_frame.h"

namespace plc_cell {
namespace test {

using Bytes = std::vector<uint8_t>;

// "03 0000 007E" -> bytes; spaces ignored.
inline Bytes hex_bytes(const std::string& s) {
  Bytes out;
  std::string digits;
  for (char c : s)
    if (c != ' ') digits += c;
  for (size_t i = 0; i + 1 < digits.size(); i += 2) out.push_back(uint8_t(std::stoi(digits.substr(i, 2), nullptr, 16)));
  return out;
}

inline int tcp_connect(int port) {
  const int fd = socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in sa{};
  sa.sin_family = AF_INET;
  sa.sin_port = htons(uint16_t(port));
  sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa) != 0) {
    close(fd);
    return -1;
  }
  return fd;
}

inline Bytes mbap(uint16_t tid, uint8_t unit, const Bytes& pdu) {
  Bytes f = {uint8_t(tid >> 8), uint8_t(tid), 0, 0, uint8_t((pdu.size() + 1) >> 8), uint8_t(pdu.size() + 1), unit};
  f.insert(f.end(), pdu.begin(), pdu.end());
  return f;
}

inline Bytes rtu(uint8_t slave, const Bytes& pdu) {
  Bytes f(pdu.size() + 3);
  f.resize(size_t(modbus::rtu_adu(slave, pdu.data(), int(pdu.size()), f.data())));
  return f;
}

inline bool write_all(int fd, const Bytes& b) {
  size_t off = 0;
  while (off < b.size()) {
    const ssize_t n = ::write(fd, b.data() + off, b.size() - off);
    if (n <= 0) return false;
    off += size_t(n);
  }
  return true;
}

// One Modbus/TCP reply (MBAP-delimited) within timeout_ms; empty on timeout or close.
inline Bytes read_tcp_reply(int fd, int timeout_ms = 5000) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  Bytes r;
  for (;;) {
    if (r.size() >= 6 && r.size() >= 6u + (size_t(r[4]) << 8 | r[5])) return r;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
    if (left <= 0) return {};
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, int(left)) <= 0) return {};
    uint8_t buf[512];
    const ssize_t n = recv(fd, buf, sizeof buf, 0);
    if (n <= 0) return {};
    r.insert(r.end(), buf, buf + n);
  }
}

// An RTU reply: bytes until a CRC-valid frame is there, within timeout_ms; empty on timeout.
inline Bytes read_rtu_reply(int fd, int timeout_ms = 2000) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::milliseconds(timeout_ms);
  Bytes r;
  for (;;) {
    if (r.size() >= 4 && modbus::crc16(r.data(), r.size() - 2) == uint16_t(r[r.size() - 2] | r[r.size() - 1] << 8))
      return r;
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
    if (left <= 0) return {};
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, int(left)) <= 0) return {};
    uint8_t buf[512];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) return {};
    r.insert(r.end(), buf, buf + n);
  }
}

// Opens a pty end raw (the client side of a socat pair).
inline int open_raw_tty(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) return -1;
  termios t{};
  tcgetattr(fd, &t);
  cfmakeraw(&t);
  tcsetattr(fd, TCSANOW, &t);
  return fd;
}

}  // namespace test
}  // namespace plc_cell
