#include "plc_cell/config/extension_registry.h"

#include <algorithm>
#include <mutex>
#include <utility>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

struct Registry {
  std::mutex mu;
  std::vector<std::pair<std::string, ExtensionFactory>> entries;
};

Registry& registry() {
  static Registry r;
  return r;
}

}  // namespace

ExtensionRegistration::ExtensionRegistration(std::string name, ExtensionFactory make) : name_(std::move(name)) {
  Registry& r = registry();
  std::lock_guard<std::mutex> lk(r.mu);
  for (const auto& e : r.entries)
    if (e.first == name_) throw Error("extension '" + name_ + "' is registered twice");
  r.entries.emplace_back(name_, std::move(make));
}

ExtensionRegistration::~ExtensionRegistration() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lk(r.mu);
  r.entries.erase(std::remove_if(r.entries.begin(), r.entries.end(), [&](const auto& e) { return e.first == name_; }),
                  r.entries.end());
}

std::vector<std::unique_ptr<CellExtension>> registered_extensions() {
  Registry& r = registry();
  std::lock_guard<std::mutex> lk(r.mu);
  std::vector<std::unique_ptr<CellExtension>> out;
  for (const auto& e : r.entries) out.push_back(e.second());
  return out;
}

}  // namespace plc_cell
