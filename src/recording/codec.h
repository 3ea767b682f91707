#pragma once
// The bytes of a recording's payload: little-endian integers, LEB128 varints and
// length-prefixed strings, written to a buffer and read back with every read bounded. A
// read past the end or a value out of its range throws FormatError with its offset.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace recording {

class FormatError : public Error {
 public:
  FormatError(size_t offset, const std::string& why) : Error(why), offset(offset) {}
  size_t offset;
};

class ByteWriter {
 public:
  void u8(uint8_t v) { out_.push_back(char(v)); }
  void u16(uint16_t v);
  void u32(uint32_t v);
  void u64(uint64_t v);
  void varint(uint64_t v);
  void string(const std::string& s);
  void raw(const void* p, size_t n) { out_.append(static_cast<const char*>(p), n); }
  std::string& bytes() { return out_; }

 private:
  std::string out_;
};

class ByteReader {
 public:
  explicit ByteReader(const std::string& bytes) : b_(bytes) {}
  uint8_t u8(const char* what);
  uint16_t u16(const char* what);
  uint32_t u32(const char* what);
  uint64_t u64(const char* what);
  uint64_t varint(const char* what);
  // A varint that must be <= max ("signal count 70000 is more than the 65536 allowed").
  uint64_t bounded(const char* what, uint64_t max);
  std::string string(const char* what, size_t max);
  void raw(void* p, size_t n, const char* what);
  size_t offset() const { return at_; }
  size_t left() const { return b_.size() - at_; }
  [[noreturn]] void fail(const std::string& why) const { throw FormatError(at_, why); }

 private:
  void need(size_t n, const char* what);
  const std::string& b_;
  size_t at_ = 0;
};

}  // namespace recording
}  // namespace plc_cell
