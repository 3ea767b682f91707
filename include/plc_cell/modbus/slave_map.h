#pragma once
// Where a Modbus protocol address lands in FBs memory: the manual's default map
// and the user-defined map of R3968..R3980. Addresses here are 0-based protocol
// addresses (what goes on the wire); docs/modbus.md relates them to 40001 style.
#include <cstdint>

#include "plc_cell/core/area.h"

namespace plc_cell {

class Memory;

namespace modbus {

enum class Table : uint8_t { Coils, DiscreteInputs, InputRegisters, HoldingRegisters };

// One contiguous run of FBs memory. For registers, index is the word-store index
// (RC counters C200..C255 take two words each, so RC word k is Modbus 9500 + k).
struct Run {
  Area area = Area::R;
  uint32_t index = 0;
};

constexpr uint16_t kUserMapMagic = 0xA55A;  // R3968
constexpr uint32_t kUserMapRegister = 3968;

// Resolves [addr, addr+count) of table t. Read at request time from m (the user
// map lives in PLC memory). False when any part is unmapped: the request gets
// exception 02. A request never spans two FBs areas.
bool resolve(const Memory& m, Table t, uint32_t addr, uint32_t count, Run* out);

// True when R3968 = A55AH switches the 0x and 4x tables to the user-defined map.
bool user_map_enabled(const Memory& m);

}  // namespace modbus
}  // namespace plc_cell
