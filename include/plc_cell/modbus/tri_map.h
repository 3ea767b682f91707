#pragma once
// The TRi map profile of the Modbus slave (docs/tri.md, "Modbus map"): Table 14.1 of
// the TRi FMD1616-10 manual on the soft PLC, through the TRi memory map
// (tri/memory_map.h). One bit table serves FC 01/02/05/15 and one word table FC
// 03/04/06/16/23 (FC01 = FC02, FC03 = FC04, writing "inputs" allowed, as on the TRi).
// Addresses are 0-based wire addresses (Modicon 4-1001 = 1000).
#include "plc_cell/modbus/map_profile.h"

namespace plc_cell {
namespace modbus {

// The TRi profile is tri_map_profile() (map_profile.h).

}  // namespace modbus
}  // namespace plc_cell
