// `plc_cell check --config` builds a cell exactly as `plc_cell sim` does, then stops, so
// the two accept and refuse the same cells with the same messages. Checked on every
// example cell and on every refusal the whole-cell fuzzer found
// (test/fuzz/corpus/rejected/).
#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "run_tool.h"

namespace plc_cell {
namespace {

std::vector<std::string> yaml_files(const std::string& dir) {
  std::vector<std::string> out;
  if (DIR* d = ::opendir(dir.c_str())) {
    while (const dirent* e = ::readdir(d)) {
      const std::string n = e->d_name;
      if (n.size() > 5 && n.compare(n.size() - 5, 5, ".yaml") == 0) out.push_back(dir + "/" + n);
    }
    ::closedir(d);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<std::string> error_lines(const std::string& out) {
  std::vector<std::string> lines;
  std::istringstream in(out);
  for (std::string l; std::getline(in, l);)
    if (l.find(": error: ") != std::string::npos) lines.push_back(l);
  return lines;
}

// Both exit 0, or both exit non-zero with the same file:line errors.
void expect_agree(const std::string& yaml) {
  const auto check = testing::run_tool("check --config " + yaml);
  const auto sim = testing::run_tool("sim --config " + yaml + " --duration 10ms");
  EXPECT_EQ(check.status == 0, sim.status == 0) << yaml << "\ncheck:\n" << check.out << "\nsim:\n" << sim.out;
  EXPECT_EQ(error_lines(check.out), error_lines(sim.out)) << yaml;
}

TEST(CheckSimAgreement, EveryExampleCell) {
  const std::string root = std::string(PLC_CELL_SOURCE_DIR) + "/examples";
  size_t n = 0;
  for (const char* d : {"conveyor", "hsc", "motion", "oven", "temp"})
    for (const std::string& y : yaml_files(root + "/" + d)) {
      expect_agree(y);
      ++n;
    }
  EXPECT_GE(n, 15u);
}

TEST(CheckSimAgreement, EveryFuzzerFoundRefusal) {
  const auto files = yaml_files(std::string(PLC_CELL_SOURCE_DIR) + "/test/fuzz/corpus/rejected");
  ASSERT_GE(files.size(), 8u);
  for (const std::string& y : files) {
    const auto check = testing::run_tool("check --config " + y);
    EXPECT_NE(check.status, 0) << y << " is a refused cell, but check accepts it:\n" << check.out;
    EXPECT_FALSE(error_lines(check.out).empty()) << y << "\n" << check.out;
    expect_agree(y);
  }
}

}  // namespace
}  // namespace plc_cell
