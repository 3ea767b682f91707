#include "plc_cell/ros/node_parameters.h"

#include <algorithm>
#include <set>

#include <ros/param.h>

#include "plc_cell/runtime/cell.h"

namespace plc_cell {

std::vector<std::string> plc_node_parameters() {
  // The node's own, read in plc_node*.cpp and the topic groups; diagnostic_period is
  // diagnostic_updater's.
  std::vector<std::string> out{"cell",        "program",          "io_rate",      "autostart",
                               "frame_id",    "counter_rate",     "motion_rate",  "temperature_rate",
                               "virtual_time", "clock_topic",     "virtual_time_lag", "publish_every_scan",
                               "clock_rate", "shared_scan", "shared_scan_threads",
                               "diagnostic_period"};
  for (const auto& spec : Cell::run_settings()) out.push_back(spec.key);
  for (const auto& k : Cell::server_kinds())
    for (const auto& s : k.settings) {
      out.push_back(k.parameter(s).substr(1));
      if (!s.retired_ros.empty()) out.push_back(s.retired_ros);  // refused with its own message
    }
  return out;
}

std::vector<std::string> unknown_parameters(const ros::NodeHandle& pnh, const std::vector<std::string>& known) {
  const std::set<std::string> names(known.begin(), known.end());
  std::vector<std::string> all;
  if (!ros::param::getParamNames(all)) return {};
  const std::string prefix = pnh.getNamespace() + "/";
  std::set<std::string> unknown;
  for (const auto& full : all) {
    if (full.compare(0, prefix.size(), prefix) != 0) continue;
    const std::string name = full.substr(prefix.size(), full.find('/', prefix.size()) - prefix.size());
    if (!names.count(name)) unknown.insert(name);
  }
  return {unknown.begin(), unknown.end()};
}

}  // namespace plc_cell
