#include "plc_cell/ros/line_node.h"

#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/param_path.h"

namespace plc_cell {

std::set<std::string> LineNode::cells_param(ros::NodeHandle& pnh) {
  std::set<std::string> cells;
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam("cells", v)) return cells;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < v.size(); ++i) {
      if (v[i].getType() != XmlRpc::XmlRpcValue::TypeString) throw Error("~cells: a list of the cells' names");
      cells.insert(static_cast<std::string>(v[i]));
    }
    return cells;
  }
  if (v.getType() != XmlRpc::XmlRpcValue::TypeString)
    throw Error("~cells: the cells' names, \"infeed,robot\" or a list; all or empty: every cell");
  // "all": what line.launch passes by default (an empty default would make roslaunch list
  // the argument as required).
  if (static_cast<std::string>(v) == "all") return cells;
  std::istringstream in(static_cast<std::string>(v));
  for (std::string name; std::getline(in, name, ',');) {
    name.erase(0, name.find_first_not_of(" \t"));
    name.erase(name.find_last_not_of(" \t") + 1);
    if (!name.empty()) cells.insert(name);
  }
  return cells;
}

LineNode::LineNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh, pnh.getNamespace()) {
  const std::string path = pnh.param<std::string>("line", "");
  if (path.empty()) throw Error("~line is not set: give the line file (docs/lines.md)");
  const std::string problem = relative_param_path_problem("the line nodelet", "line", path);
  if (!problem.empty()) throw Error(problem);
  if (pnh.param("virtual_time", false))
    throw Error("~virtual_time: a line runs in real time on ROS; plc_cell test and plc_cell sim --line run it in "
                "virtual time (docs/lines.md)");
  const bool shared = pnh.param("shared_scan", false);
  const int threads = pnh.param("shared_scan_threads", 1);
  if (threads < 1 || threads > int(SharedScanThread::kMaxThreads))
    throw Error("~shared_scan_threads must be in [1, " + std::to_string(SharedScanThread::kMaxThreads) + "]");
  line::LineOptions options;
  options.purpose = Cell::Purpose::Serve;
  options.here = cells_param(pnh);
  options.log = [](const std::string& l) { ROS_INFO("line: %s", l.c_str()); };
  try {
    line_ = std::make_unique<line::Line>(path, options);
  } catch (const SourceError&) {
    throw;  // each error at its file:line
  } catch (const std::exception& e) {
    throw Error(std::string(options.here.empty() ? "" : "~cells: ") + e.what());
  }
  nodes_.resize(line_->size());
  drivers_.assign(line_->size(), nullptr);
  for (size_t i = 0; i < line_->size(); ++i)
    if (line_->cell(i)) add_cell(nh, i);
  line_->after_scan([this](size_t cell, uint64_t) { drivers_[cell]->scanned(); });
  wires_ = std::make_unique<LineWireTopics>(nh, *line_);
  try {
    line_->start_real_time(shared ? unsigned(threads) : 0);
    wires_->start();
  } catch (...) {
    line_->stop();  // before the nodes and the wires' topics its scans call go
    throw;
  }
  updater_.setHardwareID("plc_cell/line/" + line_->name());
  updater_.add("wires", wires_.get(), &LineWireTopics::diagnose);
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  std::string here;
  for (size_t i = 0; i < line_->size(); ++i)
    if (line_->cell(i)) here += (here.empty() ? "" : ", ") + line_->entry(i).name;
  ROS_INFO("line %s (%s): cells %s here, of %s", line_->name().c_str(), line_->file().c_str(), here.c_str(),
           line_->names().c_str());
}

// The cell's plc_node side under <line>/<cell>/plc_node, as a lone plc_node's in <line>/<cell>.
void LineNode::add_cell(ros::NodeHandle& nh, size_t i) {
  const line::CellEntry& entry = line_->entry(i);
  ros::NodeHandle cell_nh(nh, line_->name() + "/" + entry.name);
  ros::NodeHandle cell_pnh(cell_nh, "plc_node");
  // What a lone plc_node's parameters say: tools that find a cell by its ~cell find this one.
  cell_pnh.setParam("cell", line_->cell(i)->config().file);
  cell_pnh.setParam("line", line_->file());
  nodes_[i] = std::make_unique<PlcNode>(cell_nh, cell_pnh, *line_->cell(i), [&](ScanDriver::Host& host) {
    auto d = std::make_unique<LineCellDriver>(cell_nh, cell_pnh, host);
    drivers_[i] = d.get();
    return d;
  });
}

LineNode::~LineNode() {
  diag_timer_.stop();
  if (line_) line_->stop();  // no scan calls a node or a wire's topic after this
  nodes_.clear();
  wires_.reset();
  line_.reset();
}

}  // namespace plc_cell
