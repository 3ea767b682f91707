#pragma once
// Reading a scenario file (docs/testing-your-cell.md). Every error of the file is found in
// one reading and thrown as one SourceError, each with file:line:column, the key and why.
#include <string>

#include "plc_cell/config/error_list.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace scenario {

Scenario load_scenario(const std::string& path);
// The same from text (tests); file names the errors and resolves the cell's path.
Scenario parse_scenario(const std::string& text, const std::string& file);
// What can be read, every error into errors instead of thrown: the cases and the steps
// that have none, so that their names can be checked against the cell in the same run.
Scenario read_scenario(const std::string& path, ErrorList& errors);
Scenario parse_scenario(const std::string& text, const std::string& file, ErrorList& errors);

}  // namespace scenario
}  // namespace plc_cell
