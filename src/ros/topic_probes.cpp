#include "plc_cell/ros/topic_probes.h"

#include <map>
#include <mutex>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {
namespace {

struct Sides {
  std::mutex mu;
  std::map<std::string, TopicProbesFactory> by_extension;
};

Sides& sides() {
  static Sides s;
  return s;
}

}  // namespace

void TopicProbes::set(TopicFeed&, const Probe& p, const Value&) {
  throw Error(check(p, true, [](const std::string&) { return true; }));
}

TopicProbesRegistration::TopicProbesRegistration(std::string extension, TopicProbesFactory make)
    : extension_(std::move(extension)) {
  Sides& s = sides();
  std::lock_guard<std::mutex> lk(s.mu);
  if (!s.by_extension.emplace(extension_, std::move(make)).second)
    throw Error("the topic probes of extension '" + extension_ + "' are registered twice");
}

TopicProbesRegistration::~TopicProbesRegistration() {
  Sides& s = sides();
  std::lock_guard<std::mutex> lk(s.mu);
  s.by_extension.erase(extension_);
}

std::vector<std::unique_ptr<TopicProbes>> registered_topic_probes() {
  Sides& s = sides();
  std::lock_guard<std::mutex> lk(s.mu);
  std::vector<std::unique_ptr<TopicProbes>> out;
  for (const auto& e : s.by_extension) out.push_back(e.second());
  return out;
}

}  // namespace scenario
}  // namespace plc_cell
