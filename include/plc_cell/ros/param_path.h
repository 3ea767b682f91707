#pragma once
// A file named by a private parameter (~cell, ~program) is opened from the node's working
// directory, and roslaunch starts nodes in ~/.ros: a relative path there is rarely what the
// launch file meant, so the error says where it looked and what to write instead.
#include <string>

namespace plc_cell {

// "" if value is empty, absolute, or a file that can be read from the working directory;
// else the node's error, e.g. for ~cell motor.yaml in ~/.ros:
// "~cell 'motor.yaml': cannot open it: No such file or directory (looked for
// /home/u/.ros/motor.yaml); plc_node runs in /home/u/.ros ..., give an absolute path ...".
std::string relative_param_path_problem(const std::string& node, const std::string& param, const std::string& value);

}  // namespace plc_cell
