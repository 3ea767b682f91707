#include "plc_cell/online/audit_log.h"

#include <sys/stat.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <ctime>
#include <fstream>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"

namespace plc_cell {
namespace online {

AuditLog::AuditLog(const std::string& program_path)
    : path_(program_path + ".changes.jsonl"), versions_(program_path + ".versions") {}

std::string utc_now() {
  const auto now = std::chrono::system_clock::now();
  const std::time_t t = std::chrono::system_clock::to_time_t(now);
  const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(now.time_since_epoch()).count() % 1000;
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[40];
  std::snprintf(buf, sizeof buf, "%04d-%02d-%02dT%02d:%02d:%02d.%03dZ", tm.tm_year + 1900, tm.tm_mon + 1, tm.tm_mday,
                tm.tm_hour, tm.tm_min, tm.tm_sec, static_cast<int>(ms));
  return buf;
}

void AuditLog::append(const ChangeOutcome& o, ChangeSource source, const std::string& reason) {
  nlohmann::json e = to_json(o);
  e["at"] = utc_now();
  e["source"] = source_text(source);
  e["reason"] = reason;
  const std::string line = e.dump() + "\n";
  std::lock_guard<std::mutex> lk(mu_);
  std::ofstream f(path_, std::ios::app | std::ios::binary);
  f << line;
  f.flush();
  if (!f) throw Error("cannot append to the change log " + path_ + ": " + std::strerror(errno));
}

nlohmann::json AuditLog::entries(size_t last) const {
  std::vector<std::string> lines;
  {
    std::lock_guard<std::mutex> lk(mu_);
    std::ifstream f(path_);
    for (std::string l; std::getline(f, l);)
      if (!l.empty()) lines.push_back(l);
  }
  nlohmann::json out = nlohmann::json::array();
  const size_t from = lines.size() > last ? lines.size() - last : 0;
  for (size_t i = from; i < lines.size(); ++i) {
    nlohmann::json e = nlohmann::json::parse(lines[i], nullptr, false);
    out.push_back(e.is_discarded() || !e.is_object() ? nlohmann::json{{"unreadable", lines[i]}} : e);
  }
  return out;
}

void AuditLog::keep_version(const std::string& hash, const std::string& text) const {
  if (mkdir(versions_.c_str(), 0755) != 0 && errno != EEXIST)
    throw Error("cannot make " + versions_ + ": " + std::strerror(errno));
  const std::string file = versions_ + "/" + hash + ".il";
  struct stat st {};
  if (stat(file.c_str(), &st) == 0) return;  // a hash names one text
  const std::string tmp = file + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw Error("cannot write " + tmp + ": " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), file.c_str()) != 0) throw Error("cannot write " + file + ": " + std::strerror(errno));
}

std::optional<std::string> AuditLog::version(const std::string& hash) const {
  return file_text(versions_ + "/" + hash + ".il");
}

std::optional<std::string> AuditLog::undo_target() const {
  std::vector<std::string> replaced;
  for (const auto& e : entries(SIZE_MAX)) {
    const std::string result = e.value("result", "");
    if (result != "applied" && result != "forced") continue;
    if (e.value("undo", false)) {
      if (!replaced.empty()) replaced.pop_back();
    } else {
      replaced.push_back(e.value("old_hash", ""));
    }
  }
  if (replaced.empty()) return std::nullopt;
  return replaced.back();
}

}  // namespace online
}  // namespace plc_cell
