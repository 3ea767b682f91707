// roslaunch starts plc_node in ~/.ros: `cell:=motor.yaml` names ~/.ros/motor.yaml. The
// node's error says where it looked and what to write instead.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "plc_cell/ros/param_path.h"

using plc_cell::relative_param_path_problem;

namespace {

// Runs the check from dir, as a node started there would, and comes back.
std::string from(const std::string& dir, const std::string& param, const std::string& value) {
  char here[4096];
  EXPECT_NE(getcwd(here, sizeof here), nullptr);
  EXPECT_EQ(chdir(dir.c_str()), 0);
  const std::string out = relative_param_path_problem("plc_node", param, value);
  EXPECT_EQ(chdir(here), 0);
  return out;
}

}  // namespace

TEST(PlcNodeParams, ARelativeCellThatIsNotThereSaysWhereItLookedAndWhatToWrite) {
  const std::string ros_home = ::testing::TempDir() + "/param_path_ros_home";
  ASSERT_EQ(std::system(("mkdir -p " + ros_home).c_str()), 0);
  char real[4096];
  ASSERT_NE(realpath(ros_home.c_str(), real), nullptr);
  const std::string dir = real;
  EXPECT_EQ(from(dir, "cell", "motor.yaml"),
            "~cell 'motor.yaml': cannot open it: No such file or directory (looked for " + dir +
                "/motor.yaml); a relative path is taken from plc_node's working directory, " + dir +
                " (roslaunch starts nodes in ~/.ros, not in the shell's directory): give an absolute path, or in "
                "a launch file $(find my_pkg)/motor.yaml for a file of the package my_pkg");
  EXPECT_NE(from(dir, "program", "cells/motor.il").find("(looked for " + dir + "/cells/motor.il)"), std::string::npos);
  // Nothing to say: an absolute path (its own error names it), nothing given, a file that is there.
  EXPECT_EQ(from(dir, "cell", "/nonexistent/motor.yaml"), "");
  EXPECT_EQ(from(dir, "cell", ""), "");
  std::ofstream(dir + "/here.yaml") << "cell: {name: t}\n";
  EXPECT_EQ(from(dir, "cell", "here.yaml"), "");
}
