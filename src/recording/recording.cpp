#include "plc_cell/recording/recording.h"

#include <cctype>

namespace plc_cell {
namespace recording {

std::string file_name_for(const std::string& case_name) {
  std::string out;
  for (unsigned char c : case_name) out += std::isalnum(c) || c == '-' || c == '_' || c == '.' ? char(c) : '_';
  if (out.empty() || out[0] == '.') out.insert(0, "case");
  return out + kExtension;
}

}  // namespace recording
}  // namespace plc_cell
