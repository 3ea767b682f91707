#pragma once
// Typed values in Modbus registers with explicit byte and word order. Our own
// codec: Debian's libmodbus 3.1.6 float helpers do not round-trip every order.
//
// Orders, with the value's bytes A (most significant) .. D/H:
//   word_order big,    byte_order big    ABCD  (Modbus standard, "big endian")
//   word_order little, byte_order big    CDAB  (word swap, common in meters)
//   word_order big,    byte_order little BADC  (byte swap)
//   word_order little, byte_order little DCBA  (little endian)
#include <cstdint>
#include <string>

namespace plc_cell {
namespace modbus {

enum class PointType : uint8_t { Bool, Int16, UInt16, Int32, UInt32, Float32, Int64, UInt64, Float64 };
enum class Order : uint8_t { Big, Little };

struct Encoding {
  PointType type = PointType::UInt16;
  Order byte_order = Order::Big;  // within each register
  Order word_order = Order::Big;  // Big: most significant register at the lowest address
};

// Throws plc_cell::Error on an unknown name ("float32", "uint16", ...).
PointType parse_point_type(const std::string& name);
Order parse_order(const std::string& name);  // "big" / "little"
const char* point_type_name(PointType t);

// Registers the type occupies (Bool: 1 bit, counted as 1).
int register_count(PointType t);
bool is_integer(PointType t);
bool is_signed(PointType t);

// The raw bit pattern, right-aligned in 64 bits, from / to registers.
uint64_t unpack(const Encoding& e, const uint16_t* regs);
void pack(const Encoding& e, uint64_t raw, uint16_t* regs);

// A decoded value: exact integers kept as integers, floats as double.
struct Value {
  PointType type = PointType::UInt16;
  uint64_t raw = 0;  // the bit pattern as on the wire (right-aligned)
  double as_double() const;
  int64_t as_int64() const;    // sign-extended for signed types, truncated for floats
  uint64_t as_uint64() const;
};

Value decode(const Encoding& e, const uint16_t* regs);
// A value as it was written: the shortest text that reads back as the same double
// (70000, not 70000.000000).
std::string format_value(double v);
// Engineering value -> raw: (value - offset) / scale, rounded for integers.
// Throws plc_cell::Error when the result does not fit the type (the value as written,
// the raw value when scale/offset changed it, the type and its bounds).
uint64_t to_raw(PointType t, double value, double scale = 1.0, double offset = 0.0);

}  // namespace modbus
}  // namespace plc_cell
