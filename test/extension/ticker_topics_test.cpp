// The made-up ticker extension's topic is built by plc_node's registry path: the cell's
// extensions iterated (add_extension_sides), its registered ROS side found by its name, its
// group published and its status on /diagnostics, with no change to plc_node.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "plc_cell/runtime/cell.h"
#include "ticker_ros.h"

using namespace plc_cell;

namespace {

struct NoInputs : StampedInputs {
  void apply_at(uint64_t, std::function<void(ScanEngine&)>) override {}
};

std::string write_cell(const std::string& name) {
  const std::string dir = ::testing::TempDir() + "/" + name;
  std::system(("mkdir -p " + dir).c_str());
  std::ofstream(dir + "/p.il") << "ORG M1925\nFUN 901\nEND\n";  // M1925: always on
  std::ofstream(dir + "/cell.yaml") << "cell: {program: p.il}\nticker: {start: 5}\n";
  return dir + "/cell.yaml";
}

TEST(MadeUpExtension, PlcNodesRegistryBuildsItsTopic) {
  ticker::Registration registered;
  ticker::RosRegistration ros_side;
  Cell cell(write_cell("ticker_topics"), {}, Cell::Purpose::Simulate);
  ros::NodeHandle nh, pnh("~");
  diagnostic_updater::Updater updater(nh, pnh);
  NoInputs inputs;
  RosSideContext ctx{nh, pnh, cell.soft(), updater, inputs};
  TopicGroups groups;
  const std::vector<std::string> diagnostics = add_extension_sides(ctx, &groups);
  EXPECT_NE(std::find(diagnostics.begin(), diagnostics.end(), "ticker"), diagnostics.end());
  std::vector<std::string> topics;
  std::vector<uint64_t> counts;
  groups.count_published(&topics, &counts);
  EXPECT_NE(std::find(topics.begin(), topics.end(), pnh.resolveName("ticker/count")), topics.end());
  EXPECT_NE(groups.layout(cell.soft()).find("ticker count\n"), std::string::npos);

  int64_t got = -1;
  ros::Subscriber sub = nh.subscribe<std_msgs::Int64>(pnh.resolveName("ticker/count"), 10,
                                                      [&](const std_msgs::Int64::ConstPtr& m) { got = m->data; });
  ASSERT_TRUE(cell.plc().set_mode(RunMode::Run));
  for (uint64_t t = 0; t < 3; ++t) cell.plc().scan(t * 1000);
  // Published until it arrives: the subscription connects in the background.
  for (int i = 0; i < 200 && got < 0; ++i) {
    groups.after_virtual_scan(uint64_t(i) * 10000, true);
    ros::Duration(0.02).sleep();
    ros::spinOnce();
  }
  EXPECT_EQ(got, 8);  // 5 from the YAML, one per scan
}

}  // namespace

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "ticker_topics_test");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
