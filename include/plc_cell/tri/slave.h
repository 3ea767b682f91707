#pragma once
// The TRi host-link slave on the soft PLC: answers decoded frames from the PLC's memory
// through memory_map.h. Transport-free, so the TCP and serial servers and the tests share
// it. A request is decoded and checked with no lock held; the PLC lock is taken for the
// memory copy only. A refused request changes nothing.
#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/writable_ranges.h"
#include "plc_cell/tri/commands.h"
#include "plc_cell/tri/frame.h"

namespace plc_cell {
namespace tri {

class Slave {
 public:
  // id: the device ID multi-point frames must carry, 0..255; throws plc_cell::Error otherwise.
  Slave(Plc& plc, int id);

  // One decoder event. Appends what is sent back to out (the echoed Ctrl-E, a response,
  // an error or framing-error response) and returns true, or returns false when the
  // slave stays silent (another ID's frame, a line without '*', garbage).
  bool handle(const Decoder::Event& ev, std::string& out);

  // A whole request as bytes, answered through a decoder of its own: the replies to
  // every frame in bytes, concatenated ("" when silent).
  std::string answer(std::string_view bytes, bool wildcard = true);

  // The response to one request (no framing): what handle() frames.
  Response execute(const Request& req);

  // Network clients may write only these (default: everything); a write elsewhere is
  // answered with error 04 and changes nothing.
  void set_writable(WritableRanges w) { writable_ = std::move(w); }

  int id() const { return id_; }
  uint64_t requests() const { return requests_; }
  uint64_t rejected() const { return rejected_; }

 private:
  Plc& plc_;
  std::atomic<int> id_;
  WritableRanges writable_;
  std::atomic<bool> halted_{false};
  std::atomic<uint64_t> requests_{0};
  std::atomic<uint64_t> rejected_{0};
};

}  // namespace tri
}  // namespace plc_cell
