#include "plc_cell/recording/recording.h"

#include "plc_cell/core/file_text.h"

#include <cctype>
#include <fstream>

namespace plc_cell {
namespace recording {

std::string file_name_for(const std::string& case_name) {
  std::string out;
  for (unsigned char c : case_name) out += std::isalnum(c) || c == '-' || c == '_' || c == '.' ? char(c) : '_';
  if (out.empty() || out[0] == '.') out.insert(0, "case");
  return out + kExtension;
}

std::string read_recording_file(const std::string& path) {
  std::optional<std::string> text = file_text(path);
  if (!text) throw Error("cannot open the recording " + path);
  return std::move(*text);
}

void write_recording_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  if (!out) throw Error("cannot write the recording " + path);
  out.write(bytes.data(), std::streamsize(bytes.size()));
  out.close();
  if (!out) throw Error("cannot write the recording " + path + " (disk full?)");
}

}  // namespace recording
}  // namespace plc_cell
