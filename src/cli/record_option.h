#pragma once
// `--record`: `plc_cell sim --record FILE` records the run, `plc_cell test --record DIR`
// each case in DIR/<case>.plcrec (docs/recordings.md); a line's run is one recording of all
// its cells (recording/line_recording.h).
#include <memory>
#include <set>
#include <string>

#include "fresh_target.h"
#include "plc_cell/line/line.h"
#include "plc_cell/recording/line_recording.h"
#include "plc_cell/recording/recorder.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace cli {

// What a recording of cell's run says about it: the program, the signals, the scan period.
recording::RecordingInfo recording_info(const Cell& cell, const std::string& source);

// "infeed.release -> robot.nest_sensor (delay 20 ms)": a wire as a line's recording and the
// monitor's overview name it.
std::string wire_text(const line::WireEntry& w);

// A line's recording, its cells' recorders started (before the line's first scan) and each
// fed after its cell's scans.
std::unique_ptr<recording::LineRecorder> record_line(line::Line& l, const std::string& source);

// A case's recording: of its cell, or of its line.
struct CaseRecording {
  std::unique_ptr<recording::Recorder> cell;
  std::unique_ptr<recording::LineRecorder> line;
};
// Starts recording the case's scans on target (before its first scan).
std::unique_ptr<CaseRecording> record_case(FreshTarget& target, const std::string& source);
// Saves the case's recording in dir, with the failure when it failed; returns its path. A
// name already in *used (two cases of one name in different files) gets "-2", "-3"...
std::string save_case(CaseRecording& rec, const scenario::CaseResult& result, const std::string& dir,
                      std::set<std::string>* used);
// The same for one recorder of its own (a case on a PLC, its polled values).
std::string save_case(recording::Recorder& rec, const scenario::CaseResult& result, const std::string& dir,
                      std::set<std::string>* used);

// The command that opens a recording in the monitor at its failure.
std::string monitor_command_for(const std::string& path);

}  // namespace cli
}  // namespace plc_cell
