#include "record_option.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"

namespace plc_cell {
namespace cli {

recording::RecordingInfo recording_info(const Cell& cell, const std::string& source) {
  recording::RecordingInfo info;
  info.source = source;
  const std::string& path = cell.program_path();
  info.program_file = path.substr(path.find_last_of('/') + 1);
  std::optional<std::string> text = file_text(path);
  if (!text) throw Error("cannot read the program " + path + " to record it");
  info.program_text = std::move(*text);
  info.signals = cell.config().signals;
  info.scan_period_us = cell.scan_period_us();
  return info;
}

std::string wire_text(const line::WireEntry& w) {
  std::string s = w.from + " -> " + w.to, how;
  if (w.part) how = "a part: travel " + scenario::format_time(w.travel_us) + ", length " + scenario::format_time(w.length_us);
  else if (w.delay_us) how = "delay " + scenario::format_time(w.delay_us);
  if (w.invert) how += (how.empty() ? "" : ", ") + std::string("inverted");
  return how.empty() ? s : s + " (" + how + ")";
}

std::unique_ptr<recording::LineRecorder> record_line(line::Line& l, const std::string& source) {
  recording::LineRecordingInfo info;
  info.source = source;
  info.line = l.name();
  for (const auto& w : l.wires()) info.wires.push_back(wire_text(w.entry));
  std::vector<std::pair<std::string, recording::RecordingInfo>> cells;
  for (size_t i = 0; i < l.size(); ++i) cells.push_back({l.entry(i).name, recording_info(*l.cell(i), source)});
  auto rec = std::make_unique<recording::LineRecorder>(info, std::move(cells));
  for (size_t i = 0; i < l.size(); ++i) rec->cell(i).start(l.cell(i)->plc());
  recording::LineRecorder* r = rec.get();
  line::Line* lp = &l;
  l.after_scan([r, lp](size_t i, uint64_t t_us) { r->cell(i).scanned(lp->cell(i)->plc(), t_us); });
  return rec;
}

std::unique_ptr<CaseRecording> record_case(FreshTarget& target, const std::string& source) {
  auto rec = std::make_unique<CaseRecording>();
  if (target.is_line()) {
    rec->line = record_line(target.line()->line(), source);
    return rec;
  }
  Cell& cell = *target.cells().front().second;
  rec->cell = std::make_unique<recording::Recorder>(recording_info(cell, source));
  rec->cell->start(cell.plc());
  recording::Recorder* r = rec->cell.get();
  Plc* plc = &cell.plc();
  target.after_scan([r, plc](size_t, uint64_t t_us) { r->scanned(*plc, t_us); });
  return rec;
}

namespace {

// dir/NAME.rec for the case, made unique among those saved in this run (*used).
std::string case_path(const std::string& case_name, const std::string& dir, std::set<std::string>* used) {
  if (::mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST)
    throw Error("cannot make the recording folder " + dir + ": " + std::strerror(errno));
  std::string name = recording::file_name_for(case_name);
  const std::string stem = name.substr(0, name.size() - std::strlen(recording::kExtension));
  for (int n = 2; !used->insert(name).second; ++n) name = stem + "-" + std::to_string(n) + recording::kExtension;
  return dir + "/" + name;
}

template <typename Recording>
void finish(Recording& rec, const scenario::CaseResult& result, const std::string& path) {
  if (!result.passed) rec.set_failure(result.virtual_us, result.failure);
  rec.save(path);
}

}  // namespace

std::string save_case(CaseRecording& rec, const scenario::CaseResult& result, const std::string& dir,
                      std::set<std::string>* used) {
  const std::string path = case_path(result.name, dir, used);
  if (rec.cell) finish(*rec.cell, result, path);
  if (rec.line) finish(*rec.line, result, path);
  return path;
}

std::string save_case(recording::Recorder& rec, const scenario::CaseResult& result, const std::string& dir,
                      std::set<std::string>* used) {
  const std::string path = case_path(result.name, dir, used);
  finish(rec, result, path);
  return path;
}

std::string monitor_command_for(const std::string& path) {
  std::string quoted = path;
  if (path.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_./-+:=") !=
      std::string::npos) {
    quoted = "'";
    for (char c : path) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    quoted += "'";
  }
  return "plc_cell monitor --recording " + quoted + " --open-at failure";
}

}  // namespace cli
}  // namespace plc_cell
