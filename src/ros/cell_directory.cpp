#include "plc_cell/ros/cell_directory.h"

#include <algorithm>
#include <cctype>

namespace plc_cell {

CellDirectory& CellDirectory::process() {
  static CellDirectory directory;
  return directory;
}

std::unique_ptr<CellDirectory::Listing> CellDirectory::list(const std::string& name, Cell& cell) {
  std::lock_guard<std::mutex> lk(mu_);
  const uint64_t id = next_++;
  cells_.push_back({id, name, &cell});
  tell();
  return std::unique_ptr<Listing>(new Listing(id));
}

CellDirectory::Listing::~Listing() { CellDirectory::process().remove(id_); }

void CellDirectory::remove(uint64_t id) {
  std::lock_guard<std::mutex> lk(mu_);
  cells_.erase(std::remove_if(cells_.begin(), cells_.end(), [id](const Entry& e) { return e.id == id; }),
               cells_.end());
  tell();  // every watcher lets go of the cell before it goes
}

uint64_t CellDirectory::watch(Watcher w) {
  std::lock_guard<std::mutex> lk(mu_);
  const uint64_t id = next_++;
  w(cells_);
  watchers_.emplace_back(id, std::move(w));
  return id;
}

void CellDirectory::unwatch(uint64_t id) {
  std::lock_guard<std::mutex> lk(mu_);
  watchers_.erase(std::remove_if(watchers_.begin(), watchers_.end(), [id](const auto& w) { return w.first == id; }),
                  watchers_.end());
}

void CellDirectory::tell() {
  for (const auto& w : watchers_) w.second(cells_);
}

std::string directory_name(const std::string& node_namespace, const std::string& node_name) {
  auto last = [](const std::string& path) {
    const size_t end = path.find_last_not_of('/');
    if (end == std::string::npos) return std::string();
    const size_t slash = path.rfind('/', end);
    return path.substr(slash == std::string::npos ? 0 : slash + 1, end - (slash == std::string::npos ? 0 : slash + 1) + 1);
  };
  std::string name = last(node_namespace);
  if (name.empty()) name = last(node_name);
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  return name.empty() ? "cell" : name;
}

}  // namespace plc_cell
