#include "plc_cell/ros/plc_node.h"

#include <std_msgs/Bool.h>

#include "plc_cell/ForcedPoints.h"
#include "plc_cell/IoState.h"
#include "plc_cell/IoWords.h"
#include "plc_cell/Signal.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/unreadable.h"
#include "plc_cell/online/il_diff.h"
#include "plc_cell/ros/extension_diagnostics.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/ros/node_parameters.h"
#include "plc_cell/ros/param_path.h"
#include "plc_cell/ros/real_time_driver.h"
#include "plc_cell/ros/register_topics.h"
#include "plc_cell/ros/server_params.h"
#include "plc_cell/ros/virtual_time_driver.h"

namespace plc_cell {

PlcNode::PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : node_name_(pnh.getNamespace()), started_(ros::WallTime::now()), updater_(nh, pnh, pnh.getNamespace()) {
  pnh.param<std::string>("cell", cell_path_, "");
  for (const char* p : {"cell", "program"}) {
    const std::string problem = relative_param_path_problem("plc_node", p, pnh.param<std::string>(p, ""));
    if (!problem.empty()) throw Error(problem);
  }
  overrides_ = cell_overrides(pnh);
  for (const auto& name : unknown_parameters(pnh, plc_node_parameters()))
    ROS_WARN("plc_node: ~%s is not a parameter of plc_node: ignored (docs/plc-node.md lists them)", name.c_str());
  own_cell_ = std::make_unique<Cell>(cell_path_, overrides_, Cell::Purpose::Serve,
                                     [](const std::string& l) { ROS_INFO("plc_node: %s", l.c_str()); });
  cell_ = own_cell_.get();
  attach(nh, pnh, [&](ScanDriver::Host&) { return make_driver(nh, pnh); });
}

PlcNode::PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh, Cell& cell, const DriverFactory& make_driver)
    : cell_(&cell), node_name_(pnh.getNamespace()), started_(ros::WallTime::now()),
      updater_(nh, pnh, pnh.getNamespace()) {
  cell_path_ = cell.config().file;
  attach(nh, pnh, make_driver);
}

void PlcNode::attach(ros::NodeHandle& nh, ros::NodeHandle& pnh, const DriverFactory& make_driver) {
  program_path_ = cell_->program_path();
  make_diagnostics();
  frame_id_ = frame_id_param(pnh);
  // Before any subscription or service: a nodelet's callbacks may run before this returns.
  driver_ = make_driver(*this);
  make_topics(pnh);
  RosSideContext sides{nh, pnh, cell_->soft(), updater_, *this};  // each extension's topics and status
  extension_diagnostics_ = add_extension_sides(sides, &topic_groups_);
  add_register_topics(pnh, cell_->soft(), &topic_groups_);
  // Operands the PLC will refuse with ERR at run time, known from the constants at load.
  for (const auto& w : cell_->soft().warnings()) ROS_WARN("plc_node: %s", w.to_string().c_str());
  cell_->start_servers([](const Server& s) { ROS_INFO("plc_node: serving %s", s.describe().c_str()); });
  if (!cell_->servers().empty()) updater_.add("protocol servers", this, &PlcNode::diagnose_servers);
  if (autostart_ && !cell_->plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program");
  // Said once here and on /diagnostics: a cell that falls back to the interpreter says why.
  const std::string engine = cell_->plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
  ROS_INFO("plc_node: engine %s", engine.c_str());
  driver_->start();
  listed_as_ = directory_name(nh.getNamespace(), pnh.getNamespace());
  listing_ = CellDirectory::process().list(listed_as_, *cell_);
  // Last: as a nodelet, the timer's callback runs on the manager's workers at once, and every
  // check it calls reads what the lines above made (the forced set is made by make_topics).
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  ROS_INFO("plc_node: cell '%s', program %s, scan %.3f ms%s, %s", cell_->config().name.c_str(), program_path_.c_str(),
           double(cell_->scan_period_us()) / 1e3, driver_->republishes() ? "" : " of virtual time",
           autostart_ ? "RUN" : "STOP");
}

PlcNode::~PlcNode() {
  listing_.reset();  // the process's monitor lets go of the cell first
  diag_timer_.stop();  // no check reads a stopping cell
  services_.clear();  // no request writes into a stopping cell
  driver_->stop();
  if (own_cell_) cell_->stop();  // servers, scans, then the store's last image (a line stops its own)
  driver_.reset();    // and what it had still to publish
}

// ~io, ~io_words, ~forced, ~signals/<name>, ~signals_stamped/<name>, the inputs and the
// services: the same topics whichever driver runs the cell.
void PlcNode::make_topics(ros::NodeHandle& pnh) {
  double io_rate = 10.0;
  pnh.param("io_rate", io_rate, io_rate);
  pnh.param("autostart", autostart_, autostart_);
  pnh.param("publish_every_scan", every_scan_, every_scan_);
  if (!(io_rate > 0 && io_rate <= 1000)) throw Error("~io_rate must be in (0, 1000] Hz");
  io_rate_ = std::make_unique<VirtualRate>(io_rate);
  io_pub_ = pnh.advertise<IoState>("io", 10);
  io_words_pub_ = pnh.advertise<IoWords>("io_words", 10);
  forced_pub_ = pnh.advertise<ForcedPoints>("forced", 1, /*latch=*/true);
  for (const auto& s : cell_->config().signals) {
    signal_pubs_.push_back(pnh.advertise<std_msgs::Bool>("signals/" + s.first, 1, /*latch=*/true));
    stamped_pubs_.push_back(pnh.advertise<Signal>("signals_stamped/" + s.first, 100, /*latch=*/true));
    if (s.second.area != Area::X) continue;
    const uint32_t x = s.second.index;
    input_subs_.push_back(pnh.subscribe<Signal>("inputs_stamped/" + s.first, 100, [this, x](const Signal::ConstPtr& m) {
      TimedInput in;
      in.stamp_us = m->header.stamp.toNSec() / 1000;
      in.x = x;
      in.v = m->data;
      input(in);
    }));
    // No stamp: applied at once, whatever the driver.
    input_subs_.push_back(pnh.subscribe<std_msgs::Bool>("inputs/" + s.first, 10, [this, x](const std_msgs::Bool::ConstPtr& m) {
      cell_->plc().locked([&](ScanEngine& e, Memory&) {
        TimedInput in;
        in.x = x;
        in.v = m->data;
        apply(e, in);
        return 0;
      });
    }));
  }
  shown_ = std::make_unique<Shown>(2 + 2 * signal_pubs_.size());
  services_ = advertise_memory_services(pnh, *this);
  services_.push_back(pnh.advertiseService("set_run_mode", &PlcNode::on_run, this));
  services_.push_back(pnh.advertiseService("load_program", &PlcNode::on_load, this));
  services_.push_back(pnh.advertiseService("reset", &PlcNode::on_reset, this));
  services_.push_back(pnh.advertiseService("simulate", &PlcNode::on_simulate, this));
}

void PlcNode::make_diagnostics() {
  // Two nodes may run the same cell YAML (cells.launch): the node name tells them apart.
  updater_.setHardwareID("plc_cell/" + cell_->config().name + "@" + node_name_);
  updater_.add("scan", this, &PlcNode::diagnose);
  updater_.add("forced points", this, &PlcNode::diagnose_forced);
  if (cell_->persister()) updater_.add("persistence", this, &PlcNode::diagnose_persist);
}

std::unique_ptr<ScanDriver> PlcNode::make_driver(ros::NodeHandle& nh, ros::NodeHandle& pnh) {
  ScanDriver::Host& host = *this;
  if (pnh.param("virtual_time", false))
    return std::make_unique<VirtualTimeDriver>(pnh, host, updater_, cell_->scan_period_us(), frame_id_);
  return std::make_unique<RealTimeDriver>(nh, pnh, host);
}

void PlcNode::apply(ScanEngine& e, const TimedInput& in) {
  if (in.resume) {
    cell_->soft().simulation().resume(in.x);
    return;
  }
  if (in.change) {
    in.change(e);
    return;
  }
  cell_->soft().simulation().override_input(in.x);  // the topic now plays this sensor
  e.set_input(in.x, in.v);
}

void PlcNode::apply_at(uint64_t stamp_us, std::function<void(ScanEngine&)> change) {
  TimedInput in;
  in.stamp_us = stamp_us;
  in.change = std::move(change);
  input(std::move(in));
}

// ---- services: every failure is a reply with a message, never an exception ----

Address PlcNode::resolve(const std::string& text) const { return cell_->config().resolve(text); }

std::vector<uint32_t> PlcNode::read(const Address& start, uint32_t count) { return cell_->plc().read(start, count); }

void PlcNode::write(const Address& start, const std::vector<uint32_t>& raw) { cell_->plc().write(start, raw); }

void PlcNode::force(const Address& bit, bool value) {
  // Lock first, then set: the program cannot overwrite the new state in between.
  cell_->plc().force(bit, ForceAction::Disable);
  cell_->plc().force(bit, value ? ForceAction::Set : ForceAction::Reset);
}

std::vector<Address> PlcNode::release(const Address* bit) {
  std::vector<Address> points;
  if (bit) points.push_back(*bit);
  else points = cell_->plc().locked([](ScanEngine&, Memory& m) { return m.disabled_points(); });
  std::vector<Address> freed;
  for (const Address& a : points) {
    const bool was = cell_->plc().locked([&](ScanEngine&, Memory& m) { return m.disabled(a.area, a.index); });
    cell_->plc().force(a, ForceAction::Enable);
    if (was) freed.push_back(a);
  }
  return freed;
}

bool PlcNode::on_run(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  res.success = cell_->plc().set_mode(req.data ? RunMode::Run : RunMode::Stop);
  res.message = res.success ? (req.data ? "RUN" : "STOP") : "cannot RUN: no program loaded";
  return true;
}

// Through the cell's change service, as the monitor and --watch-program (docs/online-change.md).
bool PlcNode::on_load(LoadProgram::Request& req, LoadProgram::Response& res) {
  ChangeRequest r;
  r.source = ChangeSource::Service;
  r.force = req.force;
  r.reason = req.reason;
  r.text = req.text;
  if (r.text.empty()) {
    std::string path;
    {
      std::lock_guard<std::mutex> lk(path_mu_);
      path = req.path.empty() ? program_path_ : req.path;
    }
    std::optional<std::string> text = file_text(path);
    if (!text) {
      res.success = false;
      res.result = "refused";
      res.message = "cannot read " + path + ": " + why_unreadable(path);
      return true;
    }
    r.text = std::move(*text);
  }
  online::ChangeService& changes = cell_->changes();
  ChangeOutcome o;
  if (online::text_hash(r.text) == changes.hash()) {
    o.result = "applied";
    o.why = "this program is already running: nothing changed";
  } else {
    o = changes.apply(r);
  }
  res.success = o.result != "refused";
  res.result = o.result;
  res.message = o.why;
  for (const auto& e : o.errors)
    res.message += "\n" + changes.file() + ":" + std::to_string(e.line) + ":" + std::to_string(e.column) + ": " +
                   e.message;
  if (o.gate.configured && !o.gate.passed) res.message += "\ngate: " + o.gate.summary;
  res.report = to_json(o).dump();
  res.instructions = cell_->plc().locked([](ScanEngine& e, Memory&) {
    return static_cast<uint32_t>(e.program().code.size());
  });
  return true;
}

}  // namespace plc_cell
