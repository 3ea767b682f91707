#pragma once
// What the tests of the plc_cell tool ask of its output and the files it writes.
#include <fstream>
#include <sstream>
#include <string>

namespace plc_cell {
namespace testing {

inline bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

inline std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace testing
}  // namespace plc_cell
