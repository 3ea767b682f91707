#pragma once
// The device areas of an FBs-PLC and their sizes.
#include <cstdint>

namespace plc_cell {

enum class Area : uint8_t { X, Y, M, S, T, C, RT, RC, R, D, F };
constexpr int kAreaCount = 11;

constexpr bool is_discrete(Area a) { return a <= Area::C; }

// Number of addressable elements (points or registers) in an area.
uint32_t area_size(Area a);
const char* area_name(Area a);

// Counters C200..C255 are 32-bit and take two words each in the RC word store.
constexpr uint32_t kFirst32BitCounter = 200;
constexpr uint32_t kCounterCount = 256;
constexpr uint32_t kRcWordCount = kFirst32BitCounter + 2 * (kCounterCount - kFirst32BitCounter);
constexpr uint32_t rc_word_index(uint32_t counter) {
  return counter < kFirst32BitCounter ? counter
                                      : kFirst32BitCounter + 2 * (counter - kFirst32BitCounter);
}

// Special relays and registers that the scan engine maintains.
namespace special {
constexpr uint32_t kClock10ms = 1920;   // M1920: 0.01 s clock, 50 % duty
constexpr uint32_t kClock100ms = 1921;  // M1921: 0.1 s clock
constexpr uint32_t kClock1s = 1922;     // M1922: 1 s clock
constexpr uint32_t kClock1min = 1923;   // M1923: 1 min clock
constexpr uint32_t kFirstScan = 1924;   // M1924: on during the first scan after RUN
constexpr uint32_t kAlwaysOn = 1925;    // M1925: always on (plc_cell choice, docs/program-format.md)
constexpr uint32_t kFirstSpecialM = 1912;
}  // namespace special

}  // namespace plc_cell
