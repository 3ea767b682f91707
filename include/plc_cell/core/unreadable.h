#pragma once
// Why a file a user named cannot be read, in words to act on: the system's reason and the
// absolute path it was looked for at, since a relative path is taken from a working
// directory the user may not have in mind (a ROS node runs in ~/.ros).
#include <string>

namespace plc_cell {

// "" if path can be opened for reading; else, for instance,
// "No such file or directory (looked for /home/u/.ros/motor.yaml)".
std::string why_unreadable(const std::string& path);

}  // namespace plc_cell
