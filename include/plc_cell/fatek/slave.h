#pragma once
// The FATEK slave: answers decoded frames from the soft PLC's memory. Transport-free,
// so the TCP and serial servers (and tests) share it. Thread-safe (Plc serialises).
#include <atomic>
#include <cstdint>
#include <string>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/fatek/protocol.h"

namespace plc_cell {
namespace fatek {

// STATUS1 bits of commands 40/53 (spec 1.9).
constexpr uint8_t kStatusRun = 0x01;
constexpr uint8_t kStatusLadderChecksum = 0x04;  // plc_cell: set when no program is loaded
constexpr uint8_t kStatusWatchdog = 0x10;

class Slave {
 public:
  // station 1..254; throws plc_cell::Error otherwise.
  Slave(Plc& plc, int station);

  // Executes one frame. Appends the response to out and returns true, or returns false when
  // nothing is to be sent (another station's frame, or broadcast station 0).
  // A rejected request changes nothing: it is validated completely before it is applied.
  bool handle(const Frame& f, std::string& out);

  // Network clients may write only these (default: everything). A write elsewhere is
  // answered with error A (illegal address), RUN/STOP with error 4 (cannot execute).
  void set_writable(WritableRanges w) { writable_ = std::move(w); }
  const WritableRanges& writable() const { return writable_; }

  int station() const { return station_; }
  uint64_t requests() const { return requests_; }
  uint64_t rejected() const { return rejected_; }

 private:
  ErrorCode execute(const Request& req, Response* rsp);

  Plc& plc_;
  int station_;
  WritableRanges writable_;
  std::atomic<uint64_t> requests_{0};
  std::atomic<uint64_t> rejected_{0};
};

}  // namespace fatek
}  // namespace plc_cell
