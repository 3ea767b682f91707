#pragma once
// A recording read back (recording.h): its scans' instants and modes, the change events,
// and the memory after any scan, rebuilt from the nearest keyframe before it (made while
// reading, after kKeyframeChanges changes or kKeyframeScans scans, whichever comes first:
// a quiet run needs few, and no rebuild applies more than that many). Reading checks
// every byte: a file that is not a recording, of another version, cut short or damaged is
// a RecordingError naming the file, the offset and why; nothing is half-read.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/recording/image.h"
#include "plc_cell/recording/recording.h"

namespace plc_cell {
namespace recording {

constexpr size_t kKeyframeChanges = 4096;
constexpr size_t kKeyframeScans = 16384;

class ByteReader;

class Reader {
 public:
  // Throws RecordingError ("run.plcrec: offset N: why"), or Error when it cannot be read.
  static Reader load(const std::string& path);
  // The bytes of a file; name is how errors name it.
  static Reader parse(const std::string& bytes, const std::string& name);
  // An unpacked payload (a cell's in a line's recording, line_recording.h).
  static Reader parse_payload(const std::string& payload, const std::string& name);

  const RecordingInfo& info() const { return info_; }
  size_t scans() const { return scans_.size(); }
  uint64_t scan_us(size_t i) const { return scans_[i].t_us; }
  RunMode mode(size_t i) const { return scans_[i].mode; }
  RunMode initial_mode() const { return initial_mode_; }
  // How many memory cells scan i changed (0: no event at that scan).
  size_t changes(size_t i) const { return scans_[i].end - scans_[i].begin; }
  // The last scan at or before t_us (0 when t_us is before the first; scans() > 0).
  size_t scan_at(uint64_t t_us) const;
  // The next (dir > 0) or previous (dir < 0) scan after from that changed one of the cells
  // marked in `cells` (bit_cells() + word_cells() flags, numbered as image.h's cells_of),
  // or from itself when there is none.
  size_t next_change(size_t from, int dir, const std::vector<bool>& cells) const;
  // Calls f(scan, cell, value) for every change of scans first..last (indices, both
  // included), in order; f returns false to stop.
  void each_change(size_t first, size_t last, const std::function<bool(size_t, uint32_t, uint16_t)>& f) const;
  // The memory after scan i; the memory before the first scan is initial().
  void image_after(size_t i, Image* out) const;
  const Image& initial() const { return keyframes_.front(); }
  size_t keyframes() const { return keyframes_.size(); }
  // Addresses the changes of scan i touch, as text ("Y0 = 1", "D10 = 5").
  std::vector<std::string> describe_changes(size_t i) const;

 private:
  struct Change {
    uint32_t cell;  // bit cell, or bit_cells() + word cell
    uint16_t value;
  };
  struct Scan {
    uint64_t t_us;
    RunMode mode;
    size_t begin, end;  // in changes_
  };
  void read_body(ByteReader& r);
  void apply(size_t i, Image* img) const;

  RecordingInfo info_;
  RunMode initial_mode_ = RunMode::Stop;
  std::vector<Scan> scans_;
  std::vector<Change> changes_;
  std::vector<Image> keyframes_;   // [k]: the memory after the first key_scans_[k] scans
  std::vector<size_t> key_scans_;
};

}  // namespace recording
}  // namespace plc_cell
