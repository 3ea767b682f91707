#pragma once
// A case run on a PLC over its link, recorded from its polls (`plc_cell test --target ...
// --record DIR`): each poll is one scan of the recording, at its instant from the case's
// start, holding the values of the addresses the case reads and drives. The monitor opens
// it as any recording (docs/recordings.md); its source says that the values were polled
// and that the rest of memory was not read, so no one takes the zeros for the PLC's.
#include <cstdint>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/recording/recorder.h"

namespace plc_cell {
namespace hardware {

class PolledRecording {
 public:
  // source: "plc_cell test --target fatek://...: <case>"; period_us: one poll every;
  // run: the PLC was seen in RUN.
  PolledRecording(recording::RecordingInfo info, const std::string& link, size_t addresses, uint64_t period_us,
                  bool run);
  void polled(uint64_t t_us, const std::vector<Address>& addrs, const std::vector<uint32_t>& values);
  recording::Recorder& recorder() { return rec_; }

  // "polled over FATEK ...: 7 addresses every 2.000 ms; the rest of memory was not read"
  static std::string polled_note(const std::string& link, size_t addresses, uint64_t period_us);

 private:
  Plc plc_;
  recording::Recorder rec_;
  bool started_ = false;
};

}  // namespace hardware
}  // namespace plc_cell
