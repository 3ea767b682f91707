#pragma once
// Parses the IL text format of docs/program-format.md into a Program.
// Every error is reported with file, line and column; nothing is partially loaded.
#include <string>
#include <string_view>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/program.h"

namespace plc_cell {

// Throws SourceError listing every error found.
Program parse_program(std::string_view text, const std::string& file,
                      const FunctionTable& functions);
// Reads and parses a file; a missing file is a SourceError too.
Program load_program_file(const std::string& path, const FunctionTable& functions);

// One word of an IL line as the parser splits it: spaces and commas separate words, `;`
// and `//` start a comment. column: 1-based, in the line.
struct IlToken {
  std::string text;
  int column;
};
std::vector<IlToken> tokenize_il_line(const std::string& line);

// Parses an IL constant: 123, -5, K123, H1F, 0x1F, 16#1F. Returns false if not a constant.
bool parse_constant(std::string_view text, int64_t* value);

}  // namespace plc_cell
