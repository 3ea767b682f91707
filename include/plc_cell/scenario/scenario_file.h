#pragma once
// Reading a scenario file (docs/testing-your-cell.md). Every error of the file is found in
// one reading and thrown as one SourceError, each with file:line:column, the key and why.
#include <string>

#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

Scenario load_scenario(const std::string& path);
// The same from text (tests); file names the errors and resolves the cell's path.
Scenario parse_scenario(const std::string& text, const std::string& file);

}  // namespace scenario
}  // namespace plc_cell
