#include "plc_cell/monitor/source_set.h"

#include "feed.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace monitor {

void SourceSet::add(const std::string& name, Source& source) {
  // The name goes into a URL path and before the '.' of qualified names.
  if (name.empty() || name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") !=
                          std::string::npos)
    throw Error("monitor: cell name '" + name + "': letters, digits, '_' and '-' only");
  if (find(name) >= 0) throw Error("monitor: cell name '" + name + "' given twice");
  cells_.push_back(Entry{name, &source, nullptr});
}

void SourceSet::add(const std::string& name, std::unique_ptr<Source> source) {
  Source& s = *source;
  add(name, s);
  cells_.back().owned = std::move(source);
}

int SourceSet::find(const std::string& name) const {
  for (size_t i = 0; i < cells_.size(); ++i)
    if (cells_[i].name == name) return int(i);
  return -1;
}

std::string SourceSet::names() const {
  std::string out;
  for (const auto& c : cells_) out += (out.empty() ? "" : ", ") + c.name;
  return out;
}

bool SourceSet::locate(const std::string& text, Located* out) const {
  const size_t dot = text.find('.');
  if (dot == std::string::npos) return false;
  const int i = find(text.substr(0, dot));
  if (i < 0) return false;
  out->cell = size_t(i);
  try {
    out->address = resolve(text.substr(dot + 1), *cells_[size_t(i)].source->program());
  } catch (const Error& e) {
    throw Error("'" + text + "': in cell " + cells_[size_t(i)].name + ": " + e.what());
  }
  return true;
}

}  // namespace monitor
}  // namespace plc_cell
