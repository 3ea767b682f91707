// Every parameter the tables of docs/plc-node.md document is one plc_node knows: a documented parameter
// missing from plc_node_parameters() draws "is not a parameter of plc_node" when set.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "plc_cell/ros/node_parameters.h"

TEST(PlcNodeParams, EveryDocumentedParameterIsKnown) {
  std::ifstream doc(std::string(PLC_CELL_SOURCE_DIR) + "/docs/plc-node.md");
  ASSERT_TRUE(doc) << "docs/plc-node.md";
  const std::vector<std::string> known = plc_cell::plc_node_parameters();
  const std::regex row(R"(^\| `~([a-z_]+)` \|)");
  int rows = 0;
  std::string line;
  std::smatch m;
  bool in_parameters = false;  // a table whose header is "| Parameter | ..."
  while (std::getline(doc, line)) {
    if (line.rfind("| Parameter |", 0) == 0) in_parameters = true;
    else if (line.empty() || line[0] != '|') in_parameters = false;
    if (!in_parameters || !std::regex_search(line, m, row)) continue;
    ++rows;
    EXPECT_NE(std::find(known.begin(), known.end(), m[1].str()), known.end())
        << "~" << m[1] << " is documented but not a parameter plc_node knows";
  }
  EXPECT_GE(rows, 10) << "the parameter tables of docs/plc-node.md were not found";
}
