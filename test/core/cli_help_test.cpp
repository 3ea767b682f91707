// plc_cell --help lists the commands in two columns: the names, then their usage lines,
// which start in one column however long the longest name is.
#include <gtest/gtest.h>

#include <algorithm>
#include <sstream>
#include <string>
#include <vector>

#include "run_tool.h"

namespace {

// The lines between "commands:" and the blank line after them.
std::vector<std::string> command_section(const std::string& help) {
  std::istringstream in(help);
  std::vector<std::string> out;
  std::string line;
  while (std::getline(in, line) && line != "commands:") {
  }
  while (std::getline(in, line) && !line.empty()) out.push_back(line);
  return out;
}

TEST(CliHelp, UsageLinesStartInOneColumnAfterTheLongestName) {
  const auto r = plc_cell::testing::run_tool("--help");
  ASSERT_EQ(r.status, 0) << r.out;
  const std::vector<std::string> lines = command_section(r.out);
  ASSERT_GE(lines.size(), 7u) << r.out;
  std::vector<std::string> names;
  for (const std::string& l : lines)
    if (l.size() > 2 && l[2] != ' ') names.push_back(l.substr(2, l.find(' ', 2) - 2));
  for (const char* n : {"sim", "run", "check", "fatek", "test", "explore", "monitor"})
    EXPECT_NE(std::find(names.begin(), names.end(), n), names.end()) << n << " not listed:\n" << r.out;
  size_t longest = 0;
  for (const auto& n : names) longest = std::max(longest, n.size());
  // Two spaces, the name column, one space at least: then every line's text.
  const size_t column = 2 + longest + 1;
  for (const std::string& l : lines) {
    ASSERT_GT(l.size(), column) << l;
    const size_t text_from = l[2] == ' ' ? 2 : l.find(' ', 2);  // after the name, on a command's first line
    EXPECT_EQ(l.find_first_not_of(' ', text_from), column) << "'" << l << "'";
  }
  EXPECT_NE(r.out.find("\n  explore FILE.scenario.yaml"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("\n  monitor --recording FILE"), std::string::npos) << r.out;
}

}  // namespace
