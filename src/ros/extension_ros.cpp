#include "plc_cell/ros/extension_ros.h"

#include <algorithm>
#include <map>
#include <mutex>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/extension_diagnostics.h"

namespace plc_cell {
namespace {

struct Sides {
  std::mutex mu;
  std::map<std::string, TopicGroupFactory> by_extension;
};

Sides& sides() {
  static Sides s;
  return s;
}

}  // namespace

RosSideRegistration::RosSideRegistration(std::string extension, TopicGroupFactory make)
    : extension_(std::move(extension)) {
  Sides& s = sides();
  std::lock_guard<std::mutex> lk(s.mu);
  if (!s.by_extension.emplace(extension_, std::move(make)).second)
    throw Error("the ROS side of extension '" + extension_ + "' is registered twice");
}

RosSideRegistration::~RosSideRegistration() {
  Sides& s = sides();
  std::lock_guard<std::mutex> lk(s.mu);
  s.by_extension.erase(extension_);
}

void add_extension_topics(RosSideContext& ctx, TopicGroups* groups) {
  for (const auto& x : ctx.cell.extensions()) {
    TopicGroupFactory make;
    {
      Sides& s = sides();
      std::lock_guard<std::mutex> lk(s.mu);
      const auto it = s.by_extension.find(x->name());
      if (it == s.by_extension.end()) continue;  // an extension with nothing on ROS
      make = it->second;
    }
    make(ctx, groups);
  }
}

std::vector<std::string> add_extension_sides(RosSideContext& ctx, TopicGroups* groups) {
  add_extension_topics(ctx, groups);
  return add_extension_diagnostics(ctx.updater, ctx.cell);
}

}  // namespace plc_cell
