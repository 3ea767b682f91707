#pragma once
// A program's text as the mutation operators take it: its lines.
#include <sstream>
#include <string>
#include <vector>

namespace plc_cell {
namespace testing {

inline std::vector<std::string> program_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace testing
}  // namespace plc_cell
