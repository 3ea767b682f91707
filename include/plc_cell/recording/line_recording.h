#pragma once
// A recorded run of a line of cells (docs/recordings.md, "A line's recording"): each cell's
// run recorded as a lone cell's is (its program, signals, scan period, its own scans and
// changes: recorder.h), under the line's name, with its wires as text, what recorded it
// and, for a failed case, the failure. One file, format version 2: the monitor opens one
// cell of it, or all of them (LineReader).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/recording/reader.h"
#include "plc_cell/recording/recorder.h"

namespace plc_cell {
namespace recording {

struct LineRecordingInfo {
  std::string source;               // "plc_cell sim --line ...", "plc_cell test FILE: CASE"
  std::string line;                 // the line's name
  std::vector<std::string> wires;   // "infeed.part_out -> robot.part_in (delay 2 s)", file order
  std::optional<uint64_t> failure_us;
  std::string failure;
};

class LineRecorder {
 public:
  // cells: each cell's name and what its recording says of it (recording_info of its Cell).
  LineRecorder(LineRecordingInfo info, std::vector<std::pair<std::string, RecordingInfo>> cells);

  size_t size() const { return recorders_.size(); }
  // Cell i's recorder: start() before the line's first scan, scanned() after each of its scans.
  Recorder& cell(size_t i) { return *recorders_[i]; }
  // The line's failure, and each cell's (the monitor opens a cell at it).
  void set_failure(uint64_t t_us, const std::string& text);

  std::string bytes() const;
  void save(const std::string& path) const;  // throws Error naming the file

 private:
  LineRecordingInfo info_;
  std::vector<std::string> names_;
  std::vector<std::unique_ptr<Recorder>> recorders_;
};

class LineReader {
 public:
  // Throws RecordingError ("line.plcrec: offset N: why"), or Error when it cannot be read.
  static LineReader load(const std::string& path);
  static LineReader parse(const std::string& bytes, const std::string& name);

  const LineRecordingInfo& info() const { return info_; }
  size_t size() const { return cells_.size(); }
  const std::string& name(size_t i) const { return cells_[i].first; }
  const Reader& cell(size_t i) const { return cells_[i].second; }
  // The cell named name, or nullptr.
  const Reader* find(const std::string& name) const;

 private:
  LineRecordingInfo info_;
  std::vector<std::pair<std::string, Reader>> cells_;
};

// The format version in a file's header (0: too short to have one): a line's recording is
// kLineFormatVersion.
uint16_t format_version(const std::string& bytes);

}  // namespace recording
}  // namespace plc_cell
