#pragma once
// Records a run scan by scan (recording.h): after each scan, a copy of the PLC's memory
// (under the PLC lock, the memory copy only) compared with the previous one; the cells that
// differ are kept with the scan's virtual instant. Called on the thread that scans (in
// virtual time: `plc_cell sim`, `plc_cell test`).
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/recording/image.h"
#include "plc_cell/recording/recording.h"

namespace plc_cell {
namespace recording {

class Recorder {
 public:
  explicit Recorder(RecordingInfo info);

  // The memory before the first scan; required before scanned().
  void start(const Plc& plc);
  // The scan at t_us has run: its changes.
  void scanned(const Plc& plc, uint64_t t_us);
  void set_failure(uint64_t t_us, const std::string& text);

  uint64_t scans() const { return scans_; }
  // The file's bytes, and the file itself (throws Error naming the file).
  std::string bytes() const;
  // What the file packs (a cell's part of a line's recording, line_recording.h).
  std::string payload() const;
  void save(const std::string& path) const;

 private:
  RecordingInfo info_;
  Image initial_, prev_, cur_;
  uint8_t initial_mode_ = 0;
  bool started_ = false;
  uint64_t scans_ = 0;
  uint64_t last_t_ = 0;
  std::string scans_bytes_;  // the scan records, encoded as they come
};

}  // namespace recording
}  // namespace plc_cell
