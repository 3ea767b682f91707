#pragma once
// A store file with two slots, each [magic, sequence, length, CRC-32, payload]. A write
// overwrites the older slot only, so a torn or corrupt slot leaves the other one intact;
// a reader takes the valid slot with the highest sequence.
#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell {
namespace persist {

struct Slot {
  uint64_t seq = 0;
  std::vector<uint8_t> payload;
  std::string where;  // "FILE slot N", for diagnostics
};

// The valid slots of a file (0, 1 or 2). Each invalid slot adds a line to problems;
// a missing file adds nothing.
std::vector<Slot> read_slots(const std::string& path, std::vector<std::string>* problems);

class SlotFile {
 public:
  // Replaces the file atomically (write tmp + fsync + rename + fsync folder) with one whose
  // slot 0 holds (seq, payload) and slot 1 is empty; keeps it open for write().
  SlotFile(const std::string& path, uint64_t seq, const std::vector<uint8_t>& payload);
  ~SlotFile();
  SlotFile(const SlotFile&) = delete;
  SlotFile& operator=(const SlotFile&) = delete;

  // Overwrites the older slot; with sync, returns once it is on disk (fdatasync).
  // The payload must have the size given at construction. Throws Error on I/O failure.
  void write(uint64_t seq, const std::vector<uint8_t>& payload, bool sync);
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  int fd_ = -1;
  size_t slot_size_ = 0;
  int next_ = 1;
  std::vector<uint8_t> buf_;
};

}  // namespace persist
}  // namespace plc_cell
