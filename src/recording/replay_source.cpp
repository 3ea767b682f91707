#include "plc_cell/recording/replay_source.h"

#include <algorithm>

#include "plc_cell/core/il_parser.h"

namespace plc_cell {
namespace recording {

namespace {

const char kReadOnly[] = "a recording is read-only";

}  // namespace

ReplaySource::ReplaySource(Reader reader, const std::string& name, const FunctionTable& functions)
    : reader_(std::move(reader)), name_(name) {
  auto view = std::make_shared<monitor::ProgramView>();
  const RecordingInfo& info = reader_.info();
  view->file = info.program_file;
  view->text = info.program_text;
  view->signals = info.signals;
  view->version = 1;
  try {
    view->program = parse_program(info.program_text, info.program_file, functions);
  } catch (const SourceError& e) {
    throw RecordingError(name + ": the recorded program does not parse here: " + e.what());
  }
  program_ = view;
  std::lock_guard<std::mutex> lk(mu_);
  move_to(0);
}

void ReplaySource::move_to(size_t scan) {
  cursor_ = scan;
  if (reader_.scans()) reader_.image_after(scan, &image_);
  else image_ = reader_.initial();
  restore(image_, &memory_);
}

uint64_t ReplaySource::t_locked() const { return reader_.scans() ? reader_.scan_us(cursor_) : 0; }

monitor::Frame ReplaySource::read(const std::vector<Address>& addrs) {
  for (const Address& a : addrs) check_span(a, 1);  // throws naming the address
  std::lock_guard<std::mutex> lk(mu_);
  monitor::Frame f;
  f.scan = reader_.scans() ? cursor_ + 1 : 0;
  f.t_us = t_locked();
  f.mode = reader_.scans() ? reader_.mode(cursor_) : reader_.initial_mode();
  f.values.reserve(addrs.size());
  for (const Address& a : addrs) f.values.push_back(memory_.read(a));
  return f;
}

monitor::CellStatus ReplaySource::status() {
  std::lock_guard<std::mutex> lk(mu_);
  monitor::CellStatus s;
  s.mode = reader_.scans() ? reader_.mode(cursor_) : reader_.initial_mode();
  s.mode_switchable = false;
  s.scan.scans = reader_.scans() ? cursor_ + 1 : 0;
  s.forced = forced_points(image_);
  s.note = "recorded run (" + reader_.info().source + "), scan " + std::to_string(s.scan.scans) + " of " +
           std::to_string(reader_.scans());
  return s;
}

void ReplaySource::write(const Address&, const std::vector<uint32_t>&) { throw Error(kReadOnly); }
void ReplaySource::force(const Address&, ForceAction) { throw Error(kReadOnly); }
void ReplaySource::set_mode(RunMode) { throw Error(kReadOnly); }

uint64_t ReplaySource::begin_us() const { return reader_.scans() ? reader_.scan_us(0) : 0; }
uint64_t ReplaySource::end_us() const { return reader_.scans() ? reader_.scan_us(reader_.scans() - 1) : 0; }

uint64_t ReplaySource::cursor_us() const {
  std::lock_guard<std::mutex> lk(mu_);
  return t_locked();
}

void ReplaySource::seek(uint64_t t_us) {
  std::lock_guard<std::mutex> lk(mu_);
  if (reader_.scans()) move_to(reader_.scan_at(t_us));
}

void ReplaySource::step_scans(int64_t n) {
  std::lock_guard<std::mutex> lk(mu_);
  if (!reader_.scans()) return;
  const int64_t last = int64_t(reader_.scans()) - 1;
  move_to(size_t(std::max<int64_t>(0, std::min<int64_t>(last, int64_t(cursor_) + n))));
}

void ReplaySource::step_events(int64_t n) {
  std::lock_guard<std::mutex> lk(mu_);
  if (!reader_.scans()) return;
  size_t at = cursor_;
  const uint64_t count = n < 0 ? uint64_t(-(n + 1)) + 1 : uint64_t(n);
  for (uint64_t k = 0; k < count; ++k) {
    const size_t next = reader_.next_event(at, n < 0 ? -1 : 1);
    if (next == at) break;
    at = next;
  }
  move_to(at);
}

}  // namespace recording
}  // namespace plc_cell
