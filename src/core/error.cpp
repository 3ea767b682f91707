#include "plc_cell/core/error.h"

namespace plc_cell {

std::string Diagnostic::to_string() const {
  std::string s = where.file.empty() ? std::string("<input>") : where.file;
  if (where.line > 0) {
    s += ":" + std::to_string(where.line);
    if (where.column > 0) s += ":" + std::to_string(where.column);
  }
  return s + (warning ? ": warning: " : ": error: ") + message;
}

static std::string join(const std::vector<Diagnostic>& ds) {
  std::string s;
  for (const auto& d : ds) {
    if (!s.empty()) s += "\n";
    s += d.to_string();
  }
  return s;
}

SourceError::SourceError(std::vector<Diagnostic> diagnostics)
    : Error(join(diagnostics)), diagnostics_(std::move(diagnostics)) {}

SourceError SourceError::at(const std::string& file, int line, int column, const std::string& message) {
  Diagnostic d;
  d.where.file = file;
  d.where.line = line;
  d.where.column = column;
  d.message = message;
  return SourceError({d});
}

}  // namespace plc_cell
