#pragma once
// Errors raised while reading user input (addresses, programs, configs).
// The scan itself never throws: runtime faults become PLC status flags.
#include <stdexcept>
#include <string>
#include <vector>

namespace plc_cell {

class Error : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based, 0 = unknown
  int column = 0;  // 1-based, 0 = unknown
};

struct Diagnostic {
  SourceLocation where;
  std::string message;
  bool warning = false;           // what the PLC accepts but will refuse at run time
  std::string to_string() const;  // "file:line:col: error: message" (or "warning:")
};

// Thrown when a text input has one or more errors; all of them are listed.
class SourceError : public Error {
 public:
  explicit SourceError(std::vector<Diagnostic> diagnostics);
  // One error at one place.
  static SourceError at(const std::string& file, int line, int column, const std::string& message);
  const std::vector<Diagnostic>& diagnostics() const { return diagnostics_; }

 private:
  std::vector<Diagnostic> diagnostics_;
};

}  // namespace plc_cell
