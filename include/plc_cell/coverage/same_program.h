#pragma once
// Whether two parsed programs are the same program: recordings can only be summed
// instruction by instruction when file, instructions and their lines all agree.
#include <string>

#include "plc_cell/core/program.h"

namespace plc_cell {
namespace coverage {

// Empty if a and b are the same program; otherwise the first difference, in words
// ("instruction 4 (line 5) differs: OUT Y0 / OUT Y1").
std::string program_difference(const Program& a, const Program& b);

}  // namespace coverage
}  // namespace plc_cell
