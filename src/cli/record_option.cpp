#include "record_option.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace cli {

recording::RecordingInfo recording_info(const Cell& cell, const std::string& source) {
  recording::RecordingInfo info;
  info.source = source;
  const std::string& path = cell.program_path();
  info.program_file = path.substr(path.find_last_of('/') + 1);
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) throw Error("cannot read the program " + path + " to record it");
  info.program_text = text.str();
  info.signals = cell.config().signals;
  info.scan_period_us = cell.scan_period_us();
  return info;
}

std::unique_ptr<recording::Recorder> record_case(scenario::CellTarget& target, const std::string& source) {
  auto rec = std::make_unique<recording::Recorder>(recording_info(target.cell(), source));
  rec->start(target.cell().plc());
  recording::Recorder* r = rec.get();
  Plc* plc = &target.cell().plc();
  target.after_scan([r, plc](uint64_t t_us) { r->scanned(*plc, t_us); });
  return rec;
}

std::string save_case(recording::Recorder& rec, const scenario::CaseResult& result, const std::string& dir,
                      std::set<std::string>* used) {
  if (::mkdir(dir.c_str(), 0777) != 0 && errno != EEXIST)
    throw Error("cannot make the recording folder " + dir + ": " + std::strerror(errno));
  if (!result.passed) rec.set_failure(result.virtual_us, result.failure);
  std::string name = recording::file_name_for(result.name);
  const std::string stem = name.substr(0, name.size() - std::strlen(recording::kExtension));
  for (int n = 2; !used->insert(name).second; ++n) name = stem + "-" + std::to_string(n) + recording::kExtension;
  const std::string path = dir + "/" + name;
  rec.save(path);
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
