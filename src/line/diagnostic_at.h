#pragma once
// An error of a line at the place in a file that caused it.
#include <string>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace line {

inline Diagnostic error_at(const SourceLocation& at, const std::string& message) {
  Diagnostic d;
  d.where = at;
  d.message = message;
  return d;
}

}  // namespace line
}  // namespace plc_cell
