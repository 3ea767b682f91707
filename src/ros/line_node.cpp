#include "plc_cell/ros/line_node.h"

#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/ros/param_path.h"

namespace plc_cell {

namespace {

// A flag of the line node: true, false or absent; anything else is refused rather than read
// as false.
bool line_flag(ros::NodeHandle& pnh, const std::string& name) {
  XmlRpc::XmlRpcValue v;
  if (!pnh.getParam(name, v)) return false;
  if (v.getType() == XmlRpc::XmlRpcValue::TypeBoolean) return bool(v);
  std::string given = "a list or a mapping";
  if (v.getType() == XmlRpc::XmlRpcValue::TypeString) given = "the string '" + std::string(v) + "'";
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) given = "the number " + std::to_string(int(v));
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) given = "the number " + std::to_string(double(v));
  throw Error("~" + name + ": true or false, not " + given + " (docs/lines.md, \"On ROS\")");
}

}  // namespace

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
  const bool virtual_time = line_flag(pnh, "virtual_time");
  const bool shared = line_flag(pnh, "shared_scan");
  const int threads = pnh.param("shared_scan_threads", 1);
  if (threads < 1 || threads > int(SharedScanThread::kMaxThreads))
    throw Error("~shared_scan_threads must be in [1, " + std::to_string(SharedScanThread::kMaxThreads) + "]");
  options_.purpose = Cell::Purpose::Serve;
  options_.here = cells_param(pnh);
  options_.log = [](const std::string& l) { ROS_INFO("line: %s", l.c_str()); };
  try {
    line_ = std::make_unique<line::Line>(path, options_);
  } catch (const SourceError&) {
    throw;  // each error at its file:line
  } catch (const std::exception& e) {
    throw Error(std::string(options_.here.empty() ? "" : "~cells: ") + e.what());
  }
  nodes_.resize(line_->size());
  drivers_.assign(line_->size(), nullptr);
  if (virtual_time) {
    if (shared) ROS_WARN("line %s: ~shared_scan is not read in virtual time: the clock's thread scans every cell",
                         line_->name().c_str());
    start_virtual_time(nh, pnh);
  } else {
    for (size_t i = 0; i < line_->size(); ++i)
      if (line_->cell(i)) add_cell(nh, i);
    start_real_time(nh, shared ? unsigned(threads) : 0);
  }
  updater_.setHardwareID("plc_cell/line/" + line_->name());
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  std::string here;
  for (size_t i = 0; i < line_->size(); ++i)
    if (line_->cell(i)) here += (here.empty() ? "" : ", ") + line_->entry(i).name;
  ROS_INFO("line %s (%s): cells %s here, of %s, in %s time", line_->name().c_str(), line_->file().c_str(), here.c_str(),
           line_->names().c_str(), virtual_time ? "virtual" : "real");
}

void LineNode::start_real_time(ros::NodeHandle& nh, unsigned shared_threads) {
  line_->after_scan([this](size_t cell, uint64_t) { drivers_[cell]->scanned(); });
  wires_ = std::make_unique<LineWireTopics>(nh, *line_);
  try {
    line_->start_real_time(shared_threads);
    wires_->start();
  } catch (...) {
    line_->stop();  // before the nodes and the wires' topics its scans call go
    throw;
  }
  updater_.add("wires", wires_.get(), &LineWireTopics::diagnose);
}

// One clock for the cells here, which only a process that runs both ends of each of its
// wires can keep exact: a sample carried between processes would arrive at a time no clock
// message waits for, so such a line is refused rather than run off its model.
void LineNode::start_virtual_time(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  for (size_t w = 0; w < line_->wires().size(); ++w) {
    const line::Wire& wire = line_->wires()[w];
    const bool from = line_->cell(wire.from_cell) != nullptr, to = line_->cell(wire.to_cell) != nullptr;
    if (from == to) continue;
    const std::string& away = line_->entry(from ? wire.to_cell : wire.from_cell).name;
    throw Error("~virtual_time: wire " + std::to_string(w) + " (" + wire.entry.from + " -> " + wire.entry.to +
                ") joins a cell here to the cell '" + away + "' of another process: a line split over processes "
                "runs on ROS in real time only; in virtual time run the cells it joins in one process (~cells)");
  }
  clock_ = std::make_unique<LineVirtualClock>(pnh, line_->name(), updater_);
  for (size_t i = 0; i < line_->size(); ++i)
    if (line_->cell(i)) add_cell(nh, i);
  line_->after_scan([this](size_t cell, uint64_t t_us) { clock_->scanned(cell, t_us); });
  line_->run();
  clock_->start(*line_);
  reset_srv_ = nh.advertiseService(line_->name() + "/reset", &LineNode::on_reset, this);
}

// Every cell fresh from the same files, its first scan at the next clock message: the
// nodes keep their topics and services (and their subscribers), as a lone node's ~reset.
bool LineNode::on_reset(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& res) {
  std::lock_guard<std::mutex> lk(reset_mu_);
  res.success = false;
  const std::string what = "line " + line_->name() + ": reset: ";
  std::unique_ptr<line::Line> fresh;
  try {
    fresh = std::make_unique<line::Line>(line_->file(), options_);
    fresh->run();
  } catch (const std::exception& e) {
    res.message = what + e.what() + " (the running line is kept)";
    return true;
  }
  for (size_t i = 0; i < line_->size(); ++i) {
    const std::string why = nodes_[i] ? nodes_[i]->adoption_refusal(*fresh->cell(i)) : "";
    if (!why.empty()) {
      res.message = what + "cell " + line_->entry(i).name + ": " + why + " (the running line is kept)";
      return true;
    }
  }
  fresh->after_scan([this](size_t cell, uint64_t t_us) { clock_->scanned(cell, t_us); });
  clock_->reset(*fresh, [&] {
    for (size_t i = 0; i < line_->size(); ++i)
      if (nodes_[i]) nodes_[i]->adopt(*fresh->cell(i));
    line_.swap(fresh);
  });
  fresh.reset();  // the old line: nothing refers to its cells any more
  res.success = true;
  res.message = "a fresh line from " + line_->file() + "; its first scan at the next clock message";
  return true;
}

// The cell's plc_node side under <line>/<cell>/plc_node, as a lone plc_node's in <line>/<cell>.
void LineNode::add_cell(ros::NodeHandle& nh, size_t i) {
  const line::CellEntry& entry = line_->entry(i);
  ros::NodeHandle cell_nh(nh, line_->name() + "/" + entry.name);
  ros::NodeHandle cell_pnh(cell_nh, "plc_node");
  // What a lone plc_node's parameters say: tools that find a cell by its ~cell find this one.
  cell_pnh.setParam("cell", line_->cell(i)->config().file);
  cell_pnh.setParam("line", line_->file());
  cell_pnh.setParam("virtual_time", bool(clock_));
  if (clock_) {  // as a lone plc_node in virtual time says them, for the tools that drive it
    cell_pnh.setParam("clock_topic", clock_->clock_topic());
    cell_pnh.setParam("virtual_time_lag", clock_->lag_s());
  }
  nodes_[i] = std::make_unique<PlcNode>(cell_nh, cell_pnh, *line_->cell(i), [&](ScanDriver::Host& host) {
    if (clock_) return clock_->driver(i, cell_pnh, host, line_->period_us(i));
    auto d = std::make_unique<LineCellDriver>(cell_nh, cell_pnh, host);
    drivers_[i] = d.get();
    return std::unique_ptr<ScanDriver>(std::move(d));
  });
}

LineNode::~LineNode() {
  diag_timer_.stop();
  reset_srv_.shutdown();
  if (clock_) clock_->stop();  // no clock message scans, no input reaches the clock, after this
  if (line_) line_->stop();  // no scan calls a node or a wire's topic after this
  nodes_.clear();
  wires_.reset();
  line_.reset();
  clock_.reset();
}

}  // namespace plc_cell
