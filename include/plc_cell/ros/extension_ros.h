#pragma once
// The ROS side of the cell's extensions: what each shows on plc_node, registered under the
// extension's name (config/cell_extension.h name()). plc_node iterates the cell's
// extensions, builds the topic groups each one's registered side makes, and puts each
// extension's status() on /diagnostics; so a new subsystem's topics are its own file in
// src/ros/ with one registration, and plc_node does not name it (docs/architecture.md,
// "Topics: one clock for every group").
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "plc_cell/core/scan_engine.h"
#include "plc_cell/ros/topic_group.h"
#include "plc_cell/sim/soft_cell.h"

namespace plc_cell {

// Inputs a topic gives the cell (a temperature channel's sensor): applied under the PLC
// lock, now in real time, in virtual time before the first scan at or after the stamp.
class StampedInputs {
 public:
  virtual ~StampedInputs() = default;
  virtual void apply_at(uint64_t stamp_us, std::function<void(ScanEngine&)> change) = 0;
};

// What a side is given to build its groups.
struct RosSideContext {
  ros::NodeHandle& nh;   // the node's namespace (joint_states)
  ros::NodeHandle& pnh;  // its private one (~counters/<name>)
  SoftCell& cell;
  diagnostic_updater::Updater& updater;  // for entries of its own beside status()
  StampedInputs& inputs;
};

// Adds the side's groups (none when the cell has nothing it would publish).
using TopicGroupFactory = std::function<void(RosSideContext& ctx, TopicGroups* groups)>;

// Registers the ROS side of extension for as long as the object lives (a static one in the
// side's file).
class RosSideRegistration {
 public:
  RosSideRegistration(std::string extension, TopicGroupFactory make);
  ~RosSideRegistration();
  RosSideRegistration(const RosSideRegistration&) = delete;
  RosSideRegistration& operator=(const RosSideRegistration&) = delete;

 private:
  std::string extension_;
};

// plc_node: for each extension of the cell, in order, the groups of its registered side.
void add_extension_topics(RosSideContext& ctx, TopicGroups* groups);
// plc_node, once: add_extension_topics, then every extension's status() on /diagnostics
// (add_extension_diagnostics); returns the names of those entries.
std::vector<std::string> add_extension_sides(RosSideContext& ctx, TopicGroups* groups);

}  // namespace plc_cell
