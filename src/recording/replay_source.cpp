#include "plc_cell/recording/replay_source.h"

#include <algorithm>
#include <map>

#include "plc_cell/core/il_parser.h"
#include "plc_cell/ladder/layout.h"

namespace plc_cell {
namespace recording {

namespace {

const char kReadOnly[] = "a recording is read-only";

// The most changes one history lists: a register that changes every scan of a long run
// would otherwise make a page's trend megabytes.
constexpr size_t kMaxHistoryPoints = 20000;

// The clock relays and the first-scan pulse (M1920-M1925) and the real-time clock
// (R4128-R4135) change with time alone: never an event, whoever shows them.
bool is_clock(const Address& a) {
  return (a.area == Area::M && a.index >= special::kClock10ms && a.index <= special::kAlwaysOn) ||
         (a.area == Area::R && a.index >= 4128 && a.index <= 4135);
}

// Marks a's cells but the clocks' (a W/DW view or a register pair element by element).
void mark(const Address& a, std::vector<bool>* cells) {
  const std::vector<uint32_t> c = cells_of(a);
  for (size_t k = 0; k < c.size(); ++k)
    if (!is_clock(Address{a.area, is_discrete(a.area) ? Width::Bit : Width::Word, a.index + uint32_t(k)}))
      (*cells)[c[k]] = true;
}

// The program's own addresses: every address its ladder draws, the outputs and the named
// signals.
std::vector<bool> program_cells(const monitor::ProgramView& view, const FunctionTable& functions) {
  std::vector<bool> cells(bit_cells() + word_cells(), false);
  const ladder::Layout layout = ladder::layout(view.program, view.text, view.signals, &functions);
  for (const auto& n : layout.networks)
    for (const Address& a : ladder::addresses(n)) mark(a, &cells);
  for (uint32_t y = 0; y < area_size(Area::Y); ++y) mark(Address{Area::Y, Width::Bit, y}, &cells);
  for (const auto& s : view.signals) mark(s.second, &cells);
  return cells;
}

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
  events_ = program_cells(*view, functions);
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

void ReplaySource::step_events(int64_t n, const std::vector<Address>& watched) {
  std::vector<bool> cells = events_;
  for (const Address& a : watched) mark(a, &cells);
  std::lock_guard<std::mutex> lk(mu_);
  if (!reader_.scans()) return;
  size_t at = cursor_;
  const uint64_t count = n < 0 ? uint64_t(-(n + 1)) + 1 : uint64_t(n);
  for (uint64_t k = 0; k < count; ++k) {
    const size_t next = reader_.next_change(at, n < 0 ? -1 : 1, cells);
    if (next == at) break;
    at = next;
  }
  move_to(at);
}

monitor::History ReplaySource::history(const std::vector<Address>& addrs, uint64_t from_us, uint64_t to_us) const {
  monitor::History h;
  h.series.resize(addrs.size());
  if (!reader_.scans()) return h;
  const size_t first = reader_.scan_at(from_us), last = reader_.scan_at(std::max(from_us, to_us));
  Image img;
  reader_.image_after(first, &img);
  // Per address its cells and their values; per cell the addresses it is part of.
  std::vector<std::vector<uint32_t>> cells(addrs.size());
  std::vector<std::vector<uint16_t>> values(addrs.size());
  std::map<uint32_t, std::vector<std::pair<size_t, size_t>>> users;  // cell -> (address, position)
  const uint32_t bits = bit_cells();
  for (size_t i = 0; i < addrs.size(); ++i) {
    cells[i] = cells_of(addrs[i]);
    for (size_t k = 0; k < cells[i].size(); ++k) {
      const uint32_t c = cells[i][k];
      values[i].push_back(c < bits ? img.bits[c] : img.words[c - bits]);
      users[c].push_back({i, k});
    }
    h.series[i].push_back({reader_.scan_us(first), value_of(addrs[i], values[i])});
  }
  size_t points = addrs.size();
  if (last > first)
    reader_.each_change(first + 1, last, [&](size_t scan, uint32_t cell, uint16_t v) {
      const auto u = users.find(cell);
      if (u == users.end()) return true;
      for (const auto& [i, k] : u->second) {
        values[i][k] = v;
        const uint32_t x = value_of(addrs[i], values[i]);
        auto& s = h.series[i];
        if (s.back().second == x) continue;  // a DISABLE flag, or the other half of a pair
        if (++points > kMaxHistoryPoints) {
          h.cut_us = reader_.scan_us(scan);
          return false;
        }
        if (s.back().first == reader_.scan_us(scan)) s.back().second = x;  // two cells of one scan
        else s.push_back({reader_.scan_us(scan), x});
      }
      return true;
    });
  return h;
}

std::string ReplaySource::refusal(monitor::Change) const { return kReadOnly; }

}  // namespace recording
}  // namespace plc_cell
