#include "plc_cell/modbus/codec.h"

#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace modbus {

namespace {
const char* const kNames[] = {"bool", "int16", "uint16", "int32", "uint32", "float32", "int64", "uint64", "float64"};
uint16_t swap_bytes(uint16_t w) { return uint16_t(w << 8 | w >> 8); }
}  // namespace

PointType parse_point_type(const std::string& name) {
  for (int i = 0; i < 9; ++i)
    if (name == kNames[i]) return PointType(i);
  throw Error("type '" + name + "': expected bool, int16, uint16, int32, uint32, float32, int64, uint64 or float64");
}

Order parse_order(const std::string& name) {
  if (name == "big") return Order::Big;
  if (name == "little") return Order::Little;
  throw Error("order '" + name + "': expected big or little");
}

const char* point_type_name(PointType t) { return kNames[int(t)]; }

int register_count(PointType t) {
  switch (t) {
    case PointType::Bool: case PointType::Int16: case PointType::UInt16: return 1;
    case PointType::Int32: case PointType::UInt32: case PointType::Float32: return 2;
    default: return 4;
  }
}

bool is_integer(PointType t) { return t != PointType::Float32 && t != PointType::Float64; }
bool is_signed(PointType t) { return t == PointType::Int16 || t == PointType::Int32 || t == PointType::Int64; }

uint64_t unpack(const Encoding& e, const uint16_t* regs) {
  const int n = register_count(e.type);
  uint64_t raw = 0;
  for (int i = 0; i < n; ++i) {  // i: significance rank, 0 = most significant word
    uint16_t w = regs[e.word_order == Order::Big ? i : n - 1 - i];
    if (e.byte_order == Order::Little) w = swap_bytes(w);
    raw = raw << 16 | w;
  }
  return raw;
}

void pack(const Encoding& e, uint64_t raw, uint16_t* regs) {
  const int n = register_count(e.type);
  for (int i = n - 1; i >= 0; --i) {
    uint16_t w = uint16_t(raw & 0xFFFF);
    raw >>= 16;
    if (e.byte_order == Order::Little) w = swap_bytes(w);
    regs[e.word_order == Order::Big ? i : n - 1 - i] = w;
  }
}

double Value::as_double() const {
  switch (type) {
    case PointType::Float32: {
      float f;
      const uint32_t b = uint32_t(raw);
      std::memcpy(&f, &b, 4);
      return f;
    }
    case PointType::Float64: {
      double d;
      std::memcpy(&d, &raw, 8);
      return d;
    }
    case PointType::UInt64: return double(raw);
    default: return is_signed(type) ? double(as_int64()) : double(raw);
  }
}

int64_t Value::as_int64() const {
  switch (type) {
    case PointType::Int16: return int16_t(raw);
    case PointType::Int32: return int32_t(raw);
    case PointType::Int64: return int64_t(raw);
    case PointType::Float32: case PointType::Float64: return int64_t(as_double());
    default: return int64_t(raw);
  }
}

uint64_t Value::as_uint64() const { return is_integer(type) && !is_signed(type) ? raw : uint64_t(as_int64()); }

Value decode(const Encoding& e, const uint16_t* regs) {
  Value v;
  v.type = e.type;
  v.raw = e.type == PointType::Bool ? (regs[0] != 0) : unpack(e, regs);
  return v;
}

std::string format_value(double v) {
  // The shortest text that reads back as the same double: 70000, 0.1, 1e+300.
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

uint64_t to_raw(PointType t, double value, double scale, double offset) {
  if (scale == 0 || !std::isfinite(value)) throw Error("value " + format_value(value) + " cannot be written");
  const double x = (value - offset) / scale;
  // What was asked, and the raw value it became when scale/offset turned it into another.
  const auto refuse = [&](const std::string& bounds) -> Error {
    std::string what = "value " + format_value(value);
    if (scale != 1 || offset != 0) what += " (raw " + format_value(is_integer(t) ? std::nearbyint(x) : x) + ")";
    return Error(what + " does not fit " + point_type_name(t) + " (" + bounds + ")");
  };
  const auto range = [&](double lo, double hi, const char* bounds) {
    const double r = std::nearbyint(x);
    if (!(r >= lo && r <= hi)) throw refuse(bounds);
    return r;
  };
  switch (t) {
    case PointType::Bool: return x != 0;
    case PointType::Int16: return uint16_t(int16_t(range(-32768, 32767, "-32768..32767")));
    case PointType::UInt16: return uint16_t(range(0, 65535, "0..65535"));
    case PointType::Int32: return uint32_t(int32_t(range(-2147483648.0, 2147483647.0, "-2147483648..2147483647")));
    case PointType::UInt32: return uint32_t(range(0, 4294967295.0, "0..4294967295"));
    // 2^63 and 2^64 are exact doubles; the bounds exclude them.
    case PointType::Int64: {
      const double r = std::nearbyint(x);
      if (!(r >= -9223372036854775808.0 && r < 9223372036854775808.0))
        throw refuse("-9223372036854775808..9223372036854775807");
      return uint64_t(int64_t(r));
    }
    case PointType::UInt64: {
      const double r = std::nearbyint(x);
      if (!(r >= 0 && r < 18446744073709551616.0)) throw refuse("0..18446744073709551615");
      return uint64_t(r);
    }
    case PointType::Float32: {
      if (std::fabs(x) > std::numeric_limits<float>::max()) throw refuse("magnitude at most 3.4028235e+38");
      const float f = float(x);
      uint32_t b;
      std::memcpy(&b, &f, 4);
      return b;
    }
    case PointType::Float64: {
      uint64_t b;
      std::memcpy(&b, &x, 8);
      return b;
    }
  }
  return 0;
}

}  // namespace modbus
}  // namespace plc_cell
