#pragma once
// Keeps a cell's retentive ranges across restarts (docs/reliability.md):
//  - every scan and every client write whose retentive image changed is written to
//    FILE.live (page cache, no sync): a kill -9 loses nothing that was latched;
//  - a flusher thread copies the newest image to FILE with fdatasync at least every
//    interval, and at once when a client write waits for it (sync_writes): a power cut
//    loses at most one interval, never an acknowledged write.
// Both files have two CRC-checked slots; at start the newest valid slot of the four wins.
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/durability.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/persist/slot_file.h"

namespace plc_cell {
namespace persist {

struct PersistStatus {
  std::string file;
  uint64_t seq = 0;          // newest image captured
  uint64_t durable_seq = 0;  // newest image on disk
  uint64_t flushes = 0;
  std::string restored;      // what happened at start, one line
  std::vector<std::string> problems;  // torn/corrupt slots found at start
  std::string error;         // last I/O error, "" if none
};

class Persister final : public Durability, public ScanHook {
 public:
  // Restores the newest valid image into plc's retentive ranges, then attaches itself
  // (scan hook + durability). Call before the first scan. log gets one line per event.
  Persister(Plc& plc, const PersistSettings& settings, std::function<void(const std::string&)> log = {});
  ~Persister() override;  // detaches, writes the last image durably

  PersistStatus status() const;

  uint64_t capture(const ScanEngine& e, const Memory& m) override;
  void wait(uint64_t ticket) override;
  void after_program(uint64_t now_us) override;

 private:
  uint64_t capture_locked(const ScanEngine& e, const Memory& m);
  void flusher();
  void flush_once(std::unique_lock<std::mutex>& lk);

  Plc& plc_;
  PersistSettings settings_;
  std::function<void(const std::string&)> log_;
  const ScanEngine* engine_ = nullptr;  // the Plc's own; used under its lock only
  const Memory* memory_ = nullptr;
  std::vector<uint8_t> scratch_;  // under the Plc lock
  std::unique_ptr<SlotFile> live_, durable_;

  mutable std::mutex mu_;  // everything below
  std::condition_variable cv_;
  std::vector<uint8_t> latest_;
  uint64_t seq_ = 0, durable_seq_ = 0, wanted_ = 0, flushes_ = 0;
  bool stop_ = false, flush_failed_ = false;
  std::string restored_, error_;
  std::vector<std::string> problems_;
  std::thread thread_;
};

}  // namespace persist
}  // namespace plc_cell
