#pragma once
// A recorded run (docs/recordings.md): what the file alone holds so that the monitor can
// show the run without the cell's files: the program text and its file name, the signals,
// the scan period, who recorded it, the memory before the first scan, and per scan its
// virtual instant, the mode and the memory cells that changed. A failed scenario case
// adds the failing check's instant and text.
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace recording {

constexpr uint16_t kFormatVersion = 1;
// A line's recording: one recording of format 1 per cell, under the line (line_recording.h).
constexpr uint16_t kLineFormatVersion = 2;
// What `plc_cell test --record DIR` names a case's file: DIR/<case>.plcrec.
constexpr const char* kExtension = ".plcrec";

struct RecordingInfo {
  std::string source;        // "plc_cell sim", "plc_cell test conveyor.scenario.yaml: <case>"
  std::string program_file;  // as shown to the user
  std::string program_text;  // the IL source
  std::vector<std::pair<std::string, Address>> signals;  // the cell's names, file order
  uint64_t scan_period_us = 0;
  std::optional<uint64_t> failure_us;  // a failed case's failing check
  std::string failure;                 // its text ("...: expect Y2 == 1 within 1.5 s")
};

// A file that is not a recording, is of another version, is cut short or damaged:
// "run.plcrec: offset 1234: scan 17: change index 99999 is past the memory".
class RecordingError : public Error {
 public:
  using Error::Error;
};

// A case name as a file name: letters, digits, '-', '_' and '.' kept, others '_'.
std::string file_name_for(const std::string& case_name);

// A recording's bytes from its file, and into it (each throws Error naming the file).
std::string read_recording_file(const std::string& path);
void write_recording_file(const std::string& path, const std::string& bytes);

}  // namespace recording
}  // namespace plc_cell
