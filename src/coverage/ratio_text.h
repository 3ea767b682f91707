#pragma once
// Internal to the coverage outputs: "n/of", as the text and the HTML report both print a total.
#include <cstdint>
#include <string>

namespace plc_cell {
namespace coverage {

inline std::string ratio(uint32_t n, uint32_t of) { return std::to_string(n) + "/" + std::to_string(of); }

}  // namespace coverage
}  // namespace plc_cell
