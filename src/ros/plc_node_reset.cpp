// ~reset: a fresh cell for the next test case, built from the same files and parameters.
// The cell and what its topics showed are built anew (Shown, the driver's run); the ROS
// side stays: publishers, subscribers and services keep their connections, so a driver's
// subscriptions see the fresh cell at once.
#include <sstream>

#include "plc_cell/ros/extension_diagnostics.h"
#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

namespace {

// What a cell's topics are made from: its signals, register groups and what each topic
// group of its extensions publishes. ~reset keeps the node's topics, so the fresh cell must
// give the same.
std::string topic_layout(Cell& cell, const TopicGroups& groups) {
  std::ostringstream out;
  const CellConfig& cfg = cell.config();
  for (const auto& s : cfg.signals) out << "signal " << s.first << '=' << format_address(s.second) << '\n';
  for (const auto& g : cfg.registers) out << "registers " << g.name << ' ' << g.text << ' ' << g.rate_hz << '\n';
  return out.str() + groups.layout(cell.soft());
}

// Why cell cannot replace running ("" if it can).
std::string refusal(Cell& running, const TopicGroups& groups, std::unique_ptr<Cell>* fresh, const std::string& path,
                    const CellOverrides& overrides, bool autostart) {
  if (running.persister())
    return "~reset: the cell keeps its retentive memory in " + running.persister()->status().file +
           ", so a fresh cell would not start fresh; run the tests without a persist file";
  try {
    *fresh = std::make_unique<Cell>(path, overrides, Cell::Purpose::Serve,
                                    [](const std::string& l) { ROS_INFO("plc_node: %s", l.c_str()); });
  } catch (const std::exception& e) {
    return std::string("~reset: ") + e.what() + " (the running cell is kept)";
  }
  if (topic_layout(**fresh, groups) != topic_layout(running, groups))
    return "~reset: the cell's files now give other topics (signals, register groups, counters, axes or "
           "temperature channels); restart plc_node (the running cell is kept)";
  if (autostart && !(*fresh)->plc().set_mode(RunMode::Run))
    return "~reset: cannot RUN: no program (the running cell is kept)";
  return "";
}

}  // namespace

// Memory as on start, no input pending, its first scan at the next clock message, every
// topic published again at that scan as on start. In virtual time the node spins one
// thread, and the driver swaps the cell with no scan running.
bool PlcNode::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  res.success = false;
  res.message = driver_->reset_refusal();
  std::unique_ptr<Cell> fresh;
  if (res.message.empty()) res.message = refusal(*cell_, topic_groups_, &fresh, cell_path_, overrides_, autostart_);
  if (!res.message.empty()) return true;
  std::string problem;
  driver_->reset([&] {
    Cell& cell = *fresh;
    problem = swap_cell(std::move(fresh), cell);
  });
  res.success = problem.empty();
  res.message = problem.empty() ? "a fresh cell from " + cell_path_ + "; its first scan at the next clock message" : problem;
  return true;
}

std::string PlcNode::swap_cell(std::unique_ptr<Cell> own, Cell& cell) {
  for (const auto& name : extension_diagnostics_) updater_.removeByName(name);
  listing_.reset();
  cell_->stop();  // its servers, before the fresh cell's take their ports
  own_cell_ = std::move(own);  // an old cell of its own goes here; nothing holds it any more
  cell_ = &cell;
  listing_ = CellDirectory::process().list(listed_as_, *cell_);
  topic_groups_.restart(cell_->soft());
  extension_diagnostics_ = add_extension_diagnostics(updater_, cell_->soft());
  {
    std::lock_guard<std::mutex> lk(path_mu_);
    program_path_ = cell_->program_path();
  }
  {
    std::lock_guard<std::mutex> lk(shown_mu_);
    shown_ = std::make_unique<Shown>(shown_->counts.size());
  }
  seen_any_ = false;  // between scans: the fresh cell's first scan is published
  try {
    cell_->start_servers([](const Server&) {});
  } catch (const std::exception& e) {
    return std::string("~reset: ") + e.what();
  }
  return "";
}

std::string PlcNode::adoption_refusal(Cell& fresh) {
  if (cell_->persister())
    return "the cell keeps its retentive memory in " + cell_->persister()->status().file +
           ", so a fresh cell would not start fresh; run the tests without a persist file";
  if (topic_layout(fresh, topic_groups_) != topic_layout(*cell_, topic_groups_))
    return "the cell's files now give other topics (signals, register groups, counters, axes or temperature "
           "channels); restart the line";
  return "";
}

void PlcNode::adopt(Cell& fresh) {
  const std::string problem = swap_cell(nullptr, fresh);
  if (!problem.empty()) ROS_ERROR("plc_node %s: %s", node_name_.c_str(), problem.c_str());
}

}  // namespace plc_cell
