#include "plc_cell/ros/plc_node.h"

#include <sstream>

#include <unistd.h>

#include <rosgraph_msgs/Clock.h>

#include "plc_cell/ForcedPoints.h"
#include "plc_cell/IoState.h"
#include "plc_cell/IoWords.h"
#include "plc_cell/Signal.h"
#include "plc_cell/core/error.h"
#include "plc_cell/ros/frame_id.h"
#include "plc_cell/ros/param_path.h"
#include "plc_cell/ros/node_parameters.h"
#include "plc_cell/ros/register_topics.h"
#include "plc_cell/ros/server_params.h"

namespace plc_cell {

namespace {
// Bit b of word i is point 16 i + b, as in the W views.
void pack_words(const std::vector<uint8_t>& bits, IoWords::_x_type* words) {
  for (size_t i = 0; i < bits.size() && i / 16 < words->size(); ++i)
    if (bits[i]) (*words)[i / 16] |= static_cast<uint16_t>(1u << (i % 16));
}
}  // namespace

PlcNode::PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh) : started_(ros::WallTime::now()), updater_(nh, pnh) {
  pnh.param<std::string>("cell", cell_path_, "");
  for (const char* p : {"cell", "program"}) {
    const std::string problem = relative_param_path_problem("plc_node", p, pnh.param<std::string>(p, ""));
    if (!problem.empty()) throw Error(problem);
  }
  overrides_ = cell_overrides(pnh);
  for (const auto& name : unknown_parameters(pnh, plc_node_parameters()))
    ROS_WARN("plc_node: ~%s is not a parameter of plc_node: ignored (docs/plc-node.md lists them)", name.c_str());
  cell_ = std::make_unique<Cell>(cell_path_, overrides_, Cell::Purpose::Serve,
                                 [](const std::string& l) { ROS_INFO("plc_node: %s", l.c_str()); });
  program_path_ = cell_->program_path();
  const CellConfig& cfg = cell_->config();
  const double scan_period = double(cell_->scan_period_us()) / 1e6;

  double io_rate = 10.0;
  bool autostart = true;
  pnh.param("io_rate", io_rate, io_rate);
  pnh.param("autostart", autostart, autostart);
  autostart_ = autostart;
  if (!(io_rate > 0 && io_rate <= 1000)) throw Error("~io_rate must be in (0, 1000] Hz");

  frame_id_ = frame_id_param(pnh);
  io_pub_ = pnh.advertise<IoState>("io", 10);
  io_words_pub_ = pnh.advertise<IoWords>("io_words", 10);
  forced_pub_ = pnh.advertise<ForcedPoints>("forced", 1, /*latch=*/true);
  for (const auto& s : cfg.signals) {
    signal_pubs_.push_back(pnh.advertise<std_msgs::Bool>("signals/" + s.first, 1, /*latch=*/true));
    stamped_pubs_.push_back(pnh.advertise<Signal>("signals_stamped/" + s.first, 100, /*latch=*/true));
    if (s.second.area != Area::X) continue;
    const uint32_t x = s.second.index;
    const std::string name = s.first;
    input_subs_.push_back(pnh.subscribe<Signal>("inputs_stamped/" + name, 100, [this, x](const Signal::ConstPtr& m) {
      on_stamped_input(x, m->header.stamp.toNSec() / 1000, m->data);
    }));
    input_subs_.push_back(pnh.subscribe<std_msgs::Bool>(
        "inputs/" + name, 10, [this, x, name](const std_msgs::Bool::ConstPtr& m) {
          cell_->plc().locked([&](ScanEngine& e, Memory&) {
            cell_->soft().simulation().override_input(x);  // the topic now plays this sensor
            e.set_input(x, m->data);
            return 0;
          });
        }));
  }
  services_ = advertise_memory_services(pnh, *this);
  services_.push_back(pnh.advertiseService("set_run_mode", &PlcNode::on_run, this));
  services_.push_back(pnh.advertiseService("load_program", &PlcNode::on_load, this));
  services_.push_back(pnh.advertiseService("reset", &PlcNode::on_reset, this));
  services_.push_back(pnh.advertiseService("simulate", &PlcNode::on_simulate, this));

  // Two nodes may run the same cell YAML (cells.launch): the node name tells them apart.
  updater_.setHardwareID("plc_cell/" + cfg.name + "@" + ros::this_node::getName());
  updater_.add("scan", this, &PlcNode::diagnose);
  updater_.add("forced points", this, &PlcNode::diagnose_forced);
  RosSideContext sides{nh, pnh, cell_->soft(), updater_, *this};  // each extension's topics and status
  extension_diagnostics_ = add_extension_sides(sides, &topic_groups_);
  diag_timer_ = nh.createTimer(ros::Duration(1.0), [this](const ros::TimerEvent&) { updater_.update(); });
  pnh.param("virtual_time", virtual_time_, false);
  add_register_topics(pnh, cell_->soft(), &topic_groups_);
  // Real time: the cell's clock on ~clock, from its time 0 on, so that a recording of it and
  // of the stamped inputs replays into a virtual-time plc_node (~clock_topic: ~clock).
  double clock_rate = 10.0;
  pnh.param("clock_rate", clock_rate, clock_rate);
  if (!(clock_rate >= 0 && clock_rate <= 1000)) throw Error("~clock_rate must be in [0, 1000] Hz (0: no ~clock)");
  if (!virtual_time_ && clock_rate > 0) {
    // A recorder that connects after the start gets the cell's time 0 first: a bag of
    // ~clock then starts the replayed cell where this one started.
    clock_pub_ = pnh.advertise<rosgraph_msgs::Clock>("clock", 100, [this](const ros::SingleSubscriberPublisher& p) {
      const int64_t origin = origin_ns_;
      if (origin < 0) return;  // the first scan's tick sends it
      rosgraph_msgs::Clock c;
      c.clock.fromNSec(uint64_t(origin));
      p.publish(c);
    });
    clock_timer_ = nh.createTimer(ros::Duration(1.0 / clock_rate), [this](const ros::TimerEvent&) { publish_clock(); });
  }
  // Virtual time publishes every change with its scan's stamp, and nothing else: the
  // periodic republish would add wall-clock stamps to a replay.
  if (!virtual_time_) io_timer_ = nh.createTimer(ros::Duration(1.0 / io_rate), [this](const ros::TimerEvent&) {
    Snapshot s;
    {
      std::lock_guard<std::mutex> lk(snap_mu_);
      if (!published_once_) return;
      s = last_published_;
    }
    publish(s, false);
  });

  if (cell_->persister()) updater_.add("persistence", this, &PlcNode::diagnose_persist);
  // Operands the PLC will refuse with ERR at run time, known from the constants at load.
  for (const auto& w : cell_->soft().warnings()) ROS_WARN("plc_node: %s", w.to_string().c_str());
  cell_->start_servers([](const Server& s) { ROS_INFO("plc_node: serving %s", s.describe().c_str()); });
  if (!cell_->servers().empty()) updater_.add("protocol servers", this, &PlcNode::diagnose_servers);

  if (autostart && !cell_->plc().set_mode(RunMode::Run)) throw Error("cannot RUN: no program");
  // Said once here and on /diagnostics: a cell that falls back to the interpreter says why.
  const std::string engine = cell_->plc().locked([](ScanEngine& e, Memory&) { return e.engine_status(); });
  ROS_INFO("plc_node: engine %s", engine.c_str());
  if (virtual_time_) {
    start_virtual_time(pnh, cell_->scan_period_us());
    ROS_INFO("plc_node: cell '%s', program %s, scan %.3f ms of virtual time, %s", cfg.name.c_str(),
             program_path_.c_str(), scan_period * 1e3, autostart ? "RUN" : "STOP");
    return;
  }
  // In virtual time the scans publish the groups (on_clock); a timer would stamp them now.
  topic_groups_.start_timers(nh);
  publisher_ = std::thread([this] { publisher_loop(); });
  cell_->start_scanning([this] { after_scan(); });
  ROS_INFO("plc_node: cell '%s', program %s, scan %.3f ms, %s", cfg.name.c_str(), program_path_.c_str(),
           scan_period * 1e3, autostart ? "RUN" : "STOP");
}

PlcNode::~PlcNode() {
  services_.clear();  // no request writes into a stopping cell
  cell_->stop();      // servers, scans, then the store's last image
  {
    std::lock_guard<std::mutex> lk(snap_mu_);
    stopping_ = true;
  }
  snap_cv_.notify_all();
  if (publisher_.joinable()) publisher_.join();
}

PlcNode::Snapshot PlcNode::take_snapshot() {
  return cell_->plc().locked([&](ScanEngine& e, Memory& m) {
    Snapshot s;
    s.scan_us = e.now_us();  // virtual time: the clock's time instead
    s.run = e.mode() == RunMode::Run;
    s.x.resize(256);
    s.y.resize(256);
    for (uint32_t i = 0; i < 256; ++i) {
      s.x[i] = m.bit(Area::X, i);
      s.y[i] = m.bit(Area::Y, i);
    }
    for (const auto& sig : cell_->config().signals) s.signals.push_back(m.bit(sig.second.area, sig.second.index));
    s.forced_gen = m.disabled_generation();
    return s;
  });
}

// Runs on the scan thread: compare, and hand changes to the publisher thread.
void PlcNode::after_scan() {
  Snapshot s = take_snapshot();
  if (origin_ns_ < 0) origin_ns_ = int64_t(ros::Time::now().toNSec()) - int64_t(s.scan_us) * 1000;
  std::lock_guard<std::mutex> lk(snap_mu_);
  if (published_once_ && s == last_scan_) return;
  last_scan_ = std::move(s);
  dirty_ = true;
  snap_cv_.notify_one();
}

// ~clock: the wall-clock time of the cell's time 0 first, then of its last scan.
void PlcNode::publish_clock() {
  const int64_t origin = origin_ns_;
  if (origin < 0) return;  // not scanned yet
  rosgraph_msgs::Clock c;
  if (!clock_sent_) {
    c.clock.fromNSec(uint64_t(origin));
    clock_pub_.publish(c);
    clock_sent_ = true;
  }
  const uint64_t now_us = cell_->plc().locked([](ScanEngine& e, Memory&) { return e.now_us(); });
  c.clock.fromNSec(uint64_t(origin) + now_us * 1000);
  clock_pub_.publish(c);
}

void PlcNode::publisher_loop() {
  for (;;) {
    Snapshot s;
    bool first;
    {
      std::unique_lock<std::mutex> lk(snap_mu_);
      snap_cv_.wait(lk, [this] { return dirty_ || stopping_; });
      if (stopping_) return;
      dirty_ = false;
      s = last_scan_;
      first = !published_once_;
    }
    publish(s, first);
    std::lock_guard<std::mutex> lk(snap_mu_);
    last_published_ = s;
    published_once_ = true;
  }
}

void PlcNode::publish(const Snapshot& s, bool all_signals) {
  IoState msg;
  ros::Time stamp;
  if (virtual_time_) stamp.fromNSec(s.scan_us * 1000);
  else stamp = ros::Time::now();
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id_;
  msg.run = s.run;
  msg.x.assign(s.x.begin(), s.x.end());
  msg.y.assign(s.y.begin(), s.y.end());
  io_pub_.publish(msg);
  IoWords words;
  words.header = msg.header;
  words.run = s.run;
  pack_words(s.x, &words.x);
  pack_words(s.y, &words.y);
  io_words_pub_.publish(words);
  if (virtual_time_) ++published_[0];
  Snapshot prev;
  {
    std::lock_guard<std::mutex> lk(snap_mu_);
    prev = last_published_;
  }
  if (all_signals || prev.forced_gen != s.forced_gen) {
    publish_forced(stamp);
    if (virtual_time_) ++published_[1];
  }
  for (size_t i = 0; i < signal_pubs_.size() && i < s.signals.size(); ++i) {
    if (!all_signals && i < prev.signals.size() && prev.signals[i] == s.signals[i]) continue;
    std_msgs::Bool b;
    b.data = s.signals[i];
    signal_pubs_[i].publish(b);
    Signal st;
    st.header.stamp = stamp;
    st.header.frame_id = frame_id_;
    st.data = s.signals[i];
    stamped_pubs_[i].publish(st);
    if (virtual_time_) {
      ++published_[2 + i];
      ++published_[2 + signal_pubs_.size() + i];
    }
  }
}

void PlcNode::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  struct View {
    ScanStats st;
    RunMode mode;
    std::string fault;
    uint64_t now_us;
    std::string engine;
  };
  const View v = cell_->plc().locked([](ScanEngine& e, Memory&) {
    return View{e.stats(), e.mode(), e.fault(), e.now_us(), e.engine_status()};
  });
  const ScanWindow::Summary recent = v.st.recent.summary(v.now_us);
  const ScanHealth health = assess_scan(recent, cell_->scan_period_us());
  const std::string mode = v.mode == RunMode::Run ? "RUN" : "STOP";
  if (!v.fault.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "stopped: " + v.fault);
  else if (health.level == ScanHealthLevel::Error) stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, mode + ": " + health.reason);
  else if (health.level == ScanHealthLevel::Warn || v.mode != RunMode::Run)
    stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, health.reason.empty() ? mode : mode + ": " + health.reason);
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, mode);
  {
    std::lock_guard<std::mutex> lk(path_mu_);
    stat.add("program", program_path_);
  }
  stat.add("engine", v.engine);
  stat.add("scans", v.st.scans);
  stat.add("cycle last (us)", v.st.cycle.last_ns / 1000.0);
  stat.add("cycle min (us)", v.st.cycle.min_ns / 1000.0);
  stat.add("cycle avg (us)", v.st.cycle.avg_ns() / 1000.0);
  stat.add("cycle max (us)", v.st.cycle.max_ns / 1000.0);
  stat.add("wake latency avg (us)", v.st.wake_latency.avg_ns() / 1000.0);
  stat.add("wake latency max (us)", v.st.wake_latency.max_ns / 1000.0);
  stat.add("overruns", v.st.overruns);
  stat.add("overruns, last 10 s", recent.overruns);
  stat.add("wake latency max, last 10 s (us)", recent.max_wake_latency_ns / 1000.0);
  // A respawned cell shows as a new pid with a short uptime (launch/cells.launch restarts it).
  stat.add("pid", static_cast<int>(::getpid()));
  stat.add("uptime (s)", (ros::WallTime::now() - started_).toSec());
}

// A lost serial device or a stopped server is a fault on /diagnostics; it clears itself
// when the server recovers (it reopens the device by itself).
void PlcNode::diagnose_servers(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  std::string down;
  for (const auto& s : cell_->servers()) {
    const ServerStatus st = s->status();
    const std::string name = s->describe();
    if (!st.running || !st.link_up) down += (down.empty() ? "" : "; ") + name + ": " + st.last_error;
    stat.add(name + " requests", st.requests);
    stat.add(name + " rejected", st.rejected);
    stat.add(name + " connections", st.connections);
    stat.add(name + " link", st.link_up ? "up" : "down");
    stat.add(name + " reopened", st.reopened);
    stat.add(name + " last error", st.last_error);
  }
  if (down.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "serving");
  else stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, down);
}

// The forced set is read in one lock only when Memory says it changed (a few thousand
// flag bytes, once per force or release), so the scan never pays for it.
void PlcNode::publish_forced(const ros::Time& stamp) {
  ForcedPoints msg;
  msg.header.stamp = stamp;
  std::vector<std::pair<std::string, bool>> list = cell_->plc().locked([](ScanEngine&, Memory& m) {
    std::vector<std::pair<std::string, bool>> out;
    for (const Address& a : m.disabled_points()) out.emplace_back(format_address(a), m.bit(a.area, a.index));
    return out;
  });
  for (const auto& p : list) {
    msg.addresses.push_back(p.first);
    msg.states.push_back(p.second);
  }
  forced_pub_.publish(msg);
  std::lock_guard<std::mutex> lk(forced_mu_);
  forced_ = std::move(list);
}

// A forced input or output looks like any other state in ~io: a cell that stops "for no
// reason" is often one a client locked. The list is a WARN here so that it shows.
void PlcNode::diagnose_forced(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  std::lock_guard<std::mutex> lk(forced_mu_);
  if (forced_.empty()) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "no point forced");
    return;
  }
  std::string list;
  for (const auto& p : forced_) {
    list += (list.empty() ? "" : ", ") + p.first + (p.second ? "=ON" : "=OFF");
    stat.add(p.first, p.second ? "forced ON" : "forced OFF");
  }
  stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
               std::to_string(forced_.size()) + " forced (release with ~release): " + list);
}

void PlcNode::diagnose_persist(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  const persist::PersistStatus p = cell_->persister()->status();
  if (!p.error.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::ERROR, p.error);
  else if (!p.problems.empty()) stat.summary(diagnostic_msgs::DiagnosticStatus::WARN, "started from a fallback copy");
  else stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "retentive ranges persisted");
  stat.add("file", p.file);
  stat.add("restored", p.restored);
  for (size_t i = 0; i < p.problems.size(); ++i) stat.add("store problem " + std::to_string(i + 1), p.problems[i]);
  stat.add("sequence", p.seq);
  stat.add("durable sequence", p.durable_seq);
  stat.add("flushes", p.flushes);
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

bool PlcNode::on_load(LoadProgram::Request& req, LoadProgram::Response& res) {
  try {
    if (!req.text.empty()) {
      cell_->plc().load_program_text(req.text, "<service>");
    } else {
      std::string path;
      {
        std::lock_guard<std::mutex> lk(path_mu_);
        path = req.path.empty() ? program_path_ : req.path;
      }
      cell_->plc().load_program_file(path);
      std::lock_guard<std::mutex> lk(path_mu_);
      program_path_ = path;
    }
    res.instructions = cell_->plc().locked([](ScanEngine& e, Memory&) {
      return static_cast<uint32_t>(e.program().code.size());
    });
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

}  // namespace plc_cell
