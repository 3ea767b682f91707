#pragma once
// Lines written to a temporary folder: cell YAMLs, programs and a line file, and the
// helpers the line tests share.
#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/line/line.h"

namespace plc_cell {
namespace testing {

// A folder of files, name -> text, written when made.
class LineFolder {
 public:
  LineFolder(const std::string& name, const std::map<std::string, std::string>& files) {
    std::string tmp = ::testing::TempDir();
    if (!tmp.empty() && tmp.back() == '/') tmp.pop_back();
    dir_ = tmp + "/line_" + name;
    std::system(("rm -rf " + dir_ + " && mkdir -p " + dir_).c_str());
    for (const auto& f : files) std::ofstream(dir_ + "/" + f.first) << f.second;
  }
  std::string path(const std::string& file) const { return dir_ + "/" + file; }
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_;
};

// A cell YAML of period_s scans running program (a file of the folder), with signals.
inline std::string cell_yaml(const std::string& name, const std::string& program, const std::string& period_s = "0.001",
                             const std::string& more = "") {
  return "cell: {name: " + name + ", program: " + program + "}\nplc: {scan_period: " + period_s + "}\n" + more;
}

// Every error of building path's line, one "file:line:col: error: message" a line.
inline std::string line_errors(const std::string& path) {
  try {
    line::Line l(path);
  } catch (const SourceError& e) {
    std::string s;
    for (const auto& d : e.diagnostics()) s += d.to_string() + "\n";
    return s;
  } catch (const Error& e) {
    return std::string("Error: ") + e.what();
  }
  return "";
}

// The value of a (as the cell resolves it) in cell i of l.
inline uint32_t value(line::Line& l, size_t i, const std::string& a) {
  Cell& c = *l.cell(i);
  const Address addr = c.config().resolve(a);
  return c.plc().locked([&](ScanEngine&, Memory& m) { return m.read(addr); });
}

}  // namespace testing
}  // namespace plc_cell
