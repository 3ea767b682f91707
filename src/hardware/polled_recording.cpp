#include "plc_cell/hardware/polled_recording.h"

#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace hardware {

namespace {

recording::RecordingInfo with_note(recording::RecordingInfo info, const std::string& note) {
  info.source += " (" + note + ")";
  return info;
}

}  // namespace

std::string PolledRecording::polled_note(const std::string& link, size_t addresses, uint64_t period_us) {
  return "values polled over " + link + ": " + std::to_string(addresses) + " addresses every " +
         scenario::format_time(period_us) + "; the rest of memory was not read";
}

PolledRecording::PolledRecording(recording::RecordingInfo info, const std::string& link, size_t addresses,
                                 uint64_t period_us, bool run)
    : rec_(with_note(std::move(info), polled_note(link, addresses, period_us))) {
  // The mode is recorded as the PLC showed it. This PLC only holds the polled values: it
  // never scans, and its program (the recording carries the real one) is empty.
  plc_.load_program_text("END\n", "polled");
  if (run) plc_.set_mode(RunMode::Run);
}

void PolledRecording::polled(uint64_t t_us, const std::vector<Address>& addrs, const std::vector<uint32_t>& values) {
  if (!started_) {  // the first poll is the state before the case's first step
    for (size_t i = 0; i < addrs.size() && i < values.size(); ++i) plc_.write(addrs[i], {values[i]});
    rec_.start(plc_);
    started_ = true;
    return;
  }
  for (size_t i = 0; i < addrs.size() && i < values.size(); ++i) plc_.write(addrs[i], {values[i]});
  rec_.scanned(plc_, t_us);
}

}  // namespace hardware
}  // namespace plc_cell
