#pragma once
// The TRi map profile of the Modbus slave (docs/tri.md, "Modbus map"): Table 14.1 of
// the TRi FMD1616-10 manual on the soft PLC, through the TRi memory map
// (tri/memory_map.h). One bit table serves FC 01/02/05/15 and one word table FC
// 03/04/06/16/23 (FC01 = FC02, FC03 = FC04, writing "inputs" allowed, as on the TRi).
// Addresses are 0-based wire addresses (Modicon 4-1001 = 1000).
#include <cstdint>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/core/writable_ranges.h"

namespace plc_cell {
namespace modbus {

// Which map a Modbus slave serves: the FBs manual's (slave_map.h) or the TRi's.
enum class MapProfile : uint8_t { Fbs, Tri };
// "fbs" or "tri"; throws plc_cell::Error naming the text otherwise.
MapProfile parse_map_profile(const std::string& text);

// One request's transfer on the TRi map, with the PLC lock held: every element of
// [rd_addr, +rd_count) and [wr_addr, +wr_count) (count 0: none) is resolved and the
// writes checked against writable (null: all) first; false (exception 02) when any is
// unmapped or not writable, and then nothing is changed. Writes go before reads.
bool tri_transfer(ScanEngine& e, Memory& m, bool bits, uint32_t rd_addr, uint32_t rd_count, uint32_t wr_addr,
                  uint32_t wr_count, const uint8_t* wbits, const uint16_t* wwords, uint8_t* rbits, uint16_t* rwords,
                  const WritableRanges* writable);

}  // namespace modbus
}  // namespace plc_cell
