#include "codec.h"

#include <cstring>

namespace plc_cell {
namespace recording {

void ByteWriter::u16(uint16_t v) {
  u8(uint8_t(v));
  u8(uint8_t(v >> 8));
}

void ByteWriter::u32(uint32_t v) {
  u16(uint16_t(v));
  u16(uint16_t(v >> 16));
}

void ByteWriter::u64(uint64_t v) {
  u32(uint32_t(v));
  u32(uint32_t(v >> 32));
}

void ByteWriter::varint(uint64_t v) {
  while (v >= 0x80) {
    u8(uint8_t(v) | 0x80);
    v >>= 7;
  }
  u8(uint8_t(v));
}

void ByteWriter::string(const std::string& s) {
  varint(s.size());
  out_ += s;
}

void ByteReader::need(size_t n, const char* what) {
  if (left() < n)
    fail(std::string(what) + ": " + std::to_string(n) + " byte(s) needed, " + std::to_string(left()) + " left");
}

uint8_t ByteReader::u8(const char* what) {
  need(1, what);
  return uint8_t(b_[at_++]);
}

uint16_t ByteReader::u16(const char* what) {
  need(2, what);
  const uint16_t v = uint16_t(uint8_t(b_[at_]) | uint8_t(b_[at_ + 1]) << 8);
  at_ += 2;
  return v;
}

uint32_t ByteReader::u32(const char* what) {
  need(4, what);
  const uint32_t lo = u16(what);
  return lo | uint32_t(u16(what)) << 16;
}

uint64_t ByteReader::u64(const char* what) {
  need(8, what);
  const uint64_t lo = u32(what);
  return lo | uint64_t(u32(what)) << 32;
}

uint64_t ByteReader::varint(const char* what) {
  const size_t start = at_;
  uint64_t v = 0;
  for (int shift = 0; shift < 64; shift += 7) {
    const uint8_t b = u8(what);
    if (shift == 63 && b > 1) break;
    v |= uint64_t(b & 0x7F) << shift;
    if (!(b & 0x80)) return v;
  }
  at_ = start;
  fail(std::string(what) + ": a number longer than 64 bits");
}

uint64_t ByteReader::bounded(const char* what, uint64_t max) {
  const size_t start = at_;
  const uint64_t v = varint(what);
  if (v > max) {
    at_ = start;
    fail(std::string(what) + " " + std::to_string(v) + " is more than " + std::to_string(max));
  }
  return v;
}

std::string ByteReader::string(const char* what, size_t max) {
  const size_t n = bounded(what, max);
  need(n, what);
  std::string s = b_.substr(at_, n);
  at_ += n;
  return s;
}

void ByteReader::raw(void* p, size_t n, const char* what) {
  need(n, what);
  std::memcpy(p, b_.data() + at_, n);
  at_ += n;
}

}  // namespace recording
}  // namespace plc_cell
