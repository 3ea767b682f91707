#pragma once
// A recorded run as the monitor's source (monitor/source.h): the page shows the memory
// after the scan at the cursor, and moves the cursor through monitor::Replay (seek, step
// by scans or by events: changes of the program's own addresses), and draws trends from
// the recorded history. A recording is read-only: every write, force and RUN/STOP is
// refused with "a recording is read-only".
#include <memory>
#include <mutex>
#include <string>

#include "plc_cell/core/function_table.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/monitor/source.h"
#include "plc_cell/recording/reader.h"

namespace plc_cell {
namespace recording {

class ReplaySource : public monitor::Source, public monitor::Replay {
 public:
  // functions: the instruction set the recorded program is parsed with (the cell's,
  // SoftCell::functions()). Throws RecordingError when the program in the file does not
  // parse with it. The cursor starts at the first scan.
  ReplaySource(Reader reader, const std::string& name, const FunctionTable& functions);

  // monitor::Source
  monitor::SourceKind kind() const override { return monitor::SourceKind::Replay; }
  // A recording shows what happened: nothing on it can be changed.
  std::string refusal(monitor::Change) const override;
  std::string describe() const override { return "recording " + name_; }
  std::shared_ptr<const monitor::ProgramView> program() const override { return program_; }
  monitor::Frame read(const std::vector<Address>& addrs) override;
  monitor::CellStatus status() override;
  void write(const Address& start, const std::vector<uint32_t>& values) override;
  void force(const Address& bit, ForceAction action) override;
  void set_mode(RunMode mode) override;
  monitor::Replay* replay() override { return this; }

  // monitor::Replay
  uint64_t begin_us() const override;
  uint64_t end_us() const override;
  uint64_t cursor_us() const override;
  uint64_t scans() const override { return reader_.scans(); }
  std::optional<uint64_t> failure_us() const override { return reader_.info().failure_us; }
  std::string failure_text() const override { return reader_.info().failure; }
  void seek(uint64_t t_us) override;
  void step_scans(int64_t n) override;
  void step_events(int64_t n, const std::vector<Address>& watched) override;
  monitor::History history(const std::vector<Address>& addrs, uint64_t from_us, uint64_t to_us) const override;

  const Reader& reader() const { return reader_; }
  // The cells whose change is an event without a watch table (cells_of numbering).
  const std::vector<bool>& event_cells() const { return events_; }

 private:
  void move_to(size_t scan);  // with mu_ held
  uint64_t t_locked() const;

  const Reader reader_;
  const std::string name_;
  std::shared_ptr<const monitor::ProgramView> program_;
  std::vector<bool> events_;
  mutable std::mutex mu_;
  size_t cursor_ = 0;
  Image image_;
  Memory memory_;  // image_ at the cursor, for Memory::read's address forms
};

}  // namespace recording
}  // namespace plc_cell
