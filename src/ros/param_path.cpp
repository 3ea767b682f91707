#include "plc_cell/ros/param_path.h"

#include <filesystem>

#include "plc_cell/core/unreadable.h"

namespace plc_cell {

std::string relative_param_path_problem(const std::string& node, const std::string& param, const std::string& value) {
  if (value.empty() || value[0] == '/') return "";
  const std::string why = why_unreadable(value);
  if (why.empty()) return "";
  std::error_code ec;
  const std::string cwd = std::filesystem::current_path(ec).string();
  return "~" + param + " '" + value + "': cannot open it: " + why + "; a relative path is taken from " + node +
         "'s working directory, " + (ec ? std::string("unknown") : cwd) +
         " (roslaunch starts nodes in ~/.ros, not in the shell's directory): give an absolute path, or in a "
         "launch file $(find my_pkg)/" + value + " for a file of the package my_pkg";
}

}  // namespace plc_cell
