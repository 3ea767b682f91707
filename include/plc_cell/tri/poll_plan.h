#pragma once
// The TRi elements a bridge reads and writes, named as plc_node names them (the FBs
// addresses of memory_map.h: X2 is input 3, D99 is DM[100]) or by their TRi names
// (INPUT[3], DM[100], A, HSCPV[1]), and the few host-link frames that read them
// (docs/tri.md, "tri_bridge"). Coalesced: discretes by words of 16 (one RVS frame per
// word, whatever number of points in it), ADC channels by RA runs, EEPROM integers by
// RXI runs of up to 32 words, and the same element asked twice is read once. Every other
// element is one frame each (RVD, RVI, RVH, RVS 06/07/0C/0D, Rm, Ru): the TRi has no
// multi-word read of them.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/config/register_groups.h"
#include "plc_cell/core/address.h"
#include "plc_cell/tri/client.h"
#include "plc_cell/tri/commands.h"

namespace plc_cell {
namespace tri {

// A plc_node address on the TRi (X0-X255, Y0-Y255, M0-M511, T50-T113, C0-C63 and their
// W/DW views, RT50-RT113, RC0-RC63, R3600-R3727, DR3760-DR3810, R3840-R3847,
// R3812-R3815, R3904-R3907, DR4096, DR4100, D0-D3999, F0-F3999), or a TRi name: INPUT[n] (n 1-16, 16
// inputs: WX(16(n-1))), OUTPUT[n], RELAY[n] (1-32), TIMERBIT[n] and CTRBIT[n] (1-4),
// TIMERPV[n], TIMERSV[n], CTRPV[n], CTRSV[n] (1-64), DM[n] (1-4000), A-Z, HSCPV[n]
// (1-2), ADC[n] (1-8), DAC[n] (1-4), PWM[n] (1-4), EEPROM[n] (1-4000). Throws Error naming the text and
// what a TRi has.
Address parse_point(const std::string& text);
// Throws Error when an element of count from start is not on a TRi.
void check_on_tri(const Address& start, uint32_t count);

using PollItem = RegisterSpan;

struct PollPlan {
  struct Part {
    uint32_t request = 0;  // index in requests
    uint32_t field = 0;    // value of its response
    int shift = 0;         // > 0 left, < 0 right
  };
  struct Element {
    std::vector<Part> parts;  // OR-ed together, then masked
    uint32_t mask = 0xFFFF;
  };
  std::vector<Request> requests;
  std::vector<std::vector<Element>> items;  // per item, per element
};

// Gaps of up to this many unrequested ADC channels or EEPROM words are read through.
constexpr uint32_t kMaxGap = 4;
constexpr uint32_t kMaxRxi = 32;  // RXI words per frame
constexpr uint32_t kMaxWxi = 16;  // WXI words per frame

// Throws Error (check_on_tri) for an element not on a TRi.
PollPlan plan_poll(const std::vector<PollItem>& items);
// Executes the plan; returns each item's raw elements in item order. Throws like Client.
std::vector<std::vector<uint32_t>> run_poll(Client& c, const PollPlan& plan);

// The frames that write raw elements (encode_element's bit patterns) from start: wb per
// discrete, WVS per aligned word of 16, WVD, WVI, WVH, WVS 06/07/0C/0D, Wm, Wu, WXI runs.
// Throws Error before anything is sent for an element the TRi cannot take (ADC, half of
// A-Z or HSCPV, an SV over 9999).
std::vector<Request> plan_write(const Address& start, const std::vector<uint32_t>& raw);

// The wb bit address of a discrete (docs/tri.md, §16.39): input 0000-00FF, output
// 0100-01FF, timer 0200-023F, counter 0300-033F, relay 0400-05FF.
uint32_t wb_address(const Address& bit);

}  // namespace tri
}  // namespace plc_cell
