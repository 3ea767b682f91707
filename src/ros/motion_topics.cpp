// The pulse-output axes on ROS: JointState, status, services and the run action.
#include "plc_cell/ros/motion_topics.h"

#include <sstream>

#include <actionlib/server/simple_action_server.h>
#include <sensor_msgs/JointState.h>

#include "plc_cell/AxisStatus.h"
#include "plc_cell/LoadMotionTable.h"
#include "plc_cell/MotionCommand.h"
#include "plc_cell/RunMotionTableAction.h"
#include "plc_cell/SetMotionParams.h"
#include "plc_cell/core/error.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/frame_id.h"

namespace plc_cell {

using motion::MotionUnit;
using RunServer = actionlib::SimpleActionServer<RunMotionTableAction>;

struct MotionTopics::AxisRos {
  int n = 0;
  std::string name;
  double upp = 1;
  double si = 1;  // m or rad per pulse: joint_states
  ros::Publisher status_pub;
  std::vector<ros::ServiceServer> services;
  std::unique_ptr<RunServer> run;
};

namespace {
std::string describe(const motion::TableError& e) {
  return "line " + std::to_string(e.line) + ": error " + std::to_string(e.code) + ": " + e.message;
}

bool parse(const std::string& text, motion::Table* t, std::string* msg, int* code, int* line) {
  motion::TableError e;
  if (motion::parse_table(text, t, &e)) return true;
  *code = e.code;
  *line = e.line;
  *msg = describe(e);
  return false;
}

// The axes extension on ROS, at ~motion_rate.
const RosSideRegistration kAxesSide("axes", [](RosSideContext& c, TopicGroups* groups) {
  groups->add(std::make_unique<MotionTopics>(c.nh, c.pnh, c.cell, c.pnh.param("motion_rate", 50.0)));
});

}  // namespace

template <class F>
auto MotionTopics::locked(F&& f) {
  return cell_->plc().locked([&](ScanEngine&, Memory&) { return f(*cell_->get<MotionUnit>()); });
}

MotionTopics::MotionTopics(ros::NodeHandle& nh, ros::NodeHandle& pnh, SoftCell& cell, double rate_hz)
    : cell_(&cell), frame_id_(frame_id_param(pnh)), rate_hz_(rate_hz) {
  if (!(rate_hz > 0 && rate_hz <= 1000)) throw Error("~motion_rate must be in (0, 1000] Hz");
  const motion::AxesConfig cfg = locked([](MotionUnit& u) { return u.config(); });
  for (int n = 0; n < motion::kAxes; ++n)
    if (cfg.axes[n].used) axes_.push_back(make_axis(pnh, n, cfg.axes[n]));
  if (axes_.empty()) return;
  // In the node's namespace, not private: a robot stack's robot_state_publisher listens on
  // joint_states, and a launch file remaps or namespaces it as for any driver.
  joints_pub_ = nh.advertise<sensor_msgs::JointState>("joint_states", 10);
}

std::unique_ptr<MotionTopics::AxisRos> MotionTopics::make_axis(ros::NodeHandle& pnh, int n, const motion::AxisDef& d) {
  auto a = std::make_unique<AxisRos>();
  a->n = n;
  a->name = d.name;
  a->upp = d.units_per_pulse;
  a->si = d.joint_scale();
  const std::string base = "motion/" + a->name;
  a->status_pub = pnh.advertise<AxisStatus>(base + "/status", 10);
  a->services.push_back(pnh.advertiseService<LoadMotionTable::Request, LoadMotionTable::Response>(
      base + "/load_table", [this, n](LoadMotionTable::Request& req, LoadMotionTable::Response& res) {
        motion::Table t;
        int code = 0, line = 0;
        if (!parse(req.table, &t, &res.message, &code, &line)) {
          res.success = false;
          res.error_code = code;
          res.line = line;
          return true;
        }
        std::string why;
        res.success = locked([&](MotionUnit& u) { return u.load_table(n, t, &why); });
        res.steps = res.success ? static_cast<int32_t>(t.steps.size()) : 0;
        res.message = why;
        return true;
      }));
  a->services.push_back(pnh.advertiseService<SetMotionParams::Request, SetMotionParams::Response>(
      base + "/set_params",
      [this, n](SetMotionParams::Request& req, SetMotionParams::Response& res) { return set_params(n, req, res); }));
  a->services.push_back(pnh.advertiseService<MotionCommand::Request, MotionCommand::Response>(
      base + "/command",
      [this, n](MotionCommand::Request& req, MotionCommand::Response& res) { return command(n, req, res); }));
  AxisRos* ar = a.get();
  a->run = std::make_unique<RunServer>(
      pnh, base + "/run", [this, ar](const RunMotionTableGoalConstPtr& goal) { run_goal(ar, goal); }, false);
  a->run->start();
  return a;
}

bool MotionTopics::set_params(int n, SetMotionParams::Request& req, SetMotionParams::Response& res) {
  res.success = false;
  std::vector<std::pair<int, int64_t>> changes;
  if (!motion::param_changes(req.names, req.values, &changes, &res.message)) return true;
  // The values as given against the FUN141 ranges (before they are narrowed to the
  // table's fields), on top of the axis's present ones: a refused request changes nothing.
  motion::ParamError e;
  res.success = locked([&](MotionUnit& u) {
    motion::AxisParams p;
    if (!u.params(n).updated(changes, &p, &e)) return false;
    u.set_params(n, p);
    return true;
  });
  if (!res.success) {
    res.error_code = e.code;
    res.message = e.message;
  }
  return true;
}

bool MotionTopics::command(int n, MotionCommand::Request& req, MotionCommand::Response& res) {
  std::string why;
  if (req.command == MotionCommand::Request::HOME) {
    motion::Table t;
    motion::TableError e;
    if (!motion::homing_table(req.speed, req.home_mode, &t, &e)) {
      res.success = false;
      res.message = describe(e);
      return true;
    }
    res.success = locked([&](MotionUnit& u) {
      return u.load_table(n, t, &why) && u.command(n, MotionUnit::Command::Start, &why);
    });
    res.message = why;
    return true;
  }
  MotionUnit::Command c;
  if (req.command == MotionCommand::Request::START) c = MotionUnit::Command::Start;
  else if (req.command == MotionCommand::Request::PAUSE) c = MotionUnit::Command::Pause;
  else if (req.command == MotionCommand::Request::RESUME) c = MotionUnit::Command::Resume;
  else if (req.command == MotionCommand::Request::ABORT) c = MotionUnit::Command::Abort;
  else {
    res.success = false;
    res.message = "command " + std::to_string(req.command) +
                  " unknown: START (1), PAUSE (2), RESUME (3), ABORT (4) or HOME (5)";
    return true;
  }
  res.success = locked([&](MotionUnit& u) { return u.command(n, c, &why); });
  res.message = why;
  return true;
}

void MotionTopics::run_goal(AxisRos* ar, const RunMotionTableGoalConstPtr& goal) {
  RunServer& srv = *ar->run;
  RunMotionTableResult result;
  std::string why;
  motion::Table t;
  int code = 0, line = 0;
  if (!goal->table.empty() && !parse(goal->table, &t, &result.message, &code, &line)) {
    result.error_code = code;
    srv.setAborted(result, result.message);
    return;
  }
  const bool ok = locked([&](MotionUnit& u) {
    if (!goal->table.empty() && !u.load_table(ar->n, t, &why)) return false;
    return u.command(ar->n, MotionUnit::Command::Start, &why);
  });
  if (!ok) {
    result.message = why;
    srv.setAborted(result, why);
    return;
  }
  follow_goal(ar, &result);
}

// A cancel (or a new goal, which preempts this one) decelerates the axis; the goal stays
// active with feedback until the axis stands still, so the result carries the final
// position and the axis takes the next goal at once.
void MotionTopics::follow_goal(AxisRos* ar, RunMotionTableResult* result) {
  RunServer& srv = *ar->run;
  std::string why;
  ros::Rate rate(50);
  bool cancelling = false;
  for (;;) {
    if (!ros::ok()) {  // shutting down: the scans may have stopped, do not wait
      locked([&](MotionUnit& u) { return u.command(ar->n, MotionUnit::Command::Abort, &why); });
      result->message = "node shutting down";
      srv.setAborted(*result, result->message);
      return;
    }
    if (!cancelling && srv.isPreemptRequested()) {
      locked([&](MotionUnit& u) { return u.command(ar->n, MotionUnit::Command::Abort, &why); });
      cancelling = true;
    }
    RunMotionTableFeedback fb;
    bool running = false;
    int err = 0;
    int64_t pulses = 0;
    locked([&](MotionUnit& u) {
      running = u.program_running(ar->n) || u.axis(ar->n).moving();
      err = u.error(ar->n);
      pulses = u.position(ar->n);
      fb.step = u.step(ar->n);
      fb.velocity = u.frequency(ar->n) * ar->upp * u.axis(ar->n).direction();
      return 0;
    });
    fb.position = static_cast<double>(pulses) * ar->upp;
    result->pulses = pulses;
    result->position = fb.position;
    if (!running) {
      result->error_code = err;
      if (cancelling) {
        result->message = "cancelled: decelerated stop at " + std::to_string(pulses) + " pulses";
        srv.setPreempted(*result, result->message);
      } else if (err == 0) {
        result->success = true;
        srv.setSucceeded(*result);
      } else {
        srv.setAborted(*result, "error " + std::to_string(err));
      }
      return;
    }
    srv.publishFeedback(fb);
    rate.sleep();
  }
}

std::string MotionTopics::layout(SoftCell& cell) const {
  std::ostringstream out;
  cell.plc().locked([&](ScanEngine&, Memory&) {
    const motion::AxesConfig& ac = cell.get<MotionUnit>()->config();
    for (int n = 0; n < motion::kAxes; ++n)
      if (ac.axes[n].used)
        out << "axis " << n << ' ' << ac.axes[n].name << ' ' << ac.axes[n].units_per_pulse << ' '
            << ac.axes[n].joint_scale() << '\n';
    return 0;
  });
  return out.str();
}

MotionTopics::~MotionTopics() {
  for (auto& a : axes_) a->run->shutdown();
}

std::vector<std::string> MotionTopics::topics() const {
  if (axes_.empty()) return {};  // publish() puts nothing anywhere
  std::vector<std::string> out{joints_pub_.getTopic()};
  for (const auto& a : axes_) out.push_back(a->status_pub.getTopic());
  return out;
}

void MotionTopics::publish(const ros::Time& stamp) {
  if (axes_.empty()) return;
  struct Reading {
    int64_t pulses;
    double frequency;  // signed by the direction
    int32_t remaining, step, error;
    bool busy, running, finished;
  };
  std::vector<Reading> r(axes_.size());
  cell_->plc().locked([&](ScanEngine&, Memory&) {
    MotionUnit& u = *cell_->get<MotionUnit>();
    for (size_t i = 0; i < axes_.size(); ++i) {
      const int n = axes_[i]->n;
      r[i] = {u.position(n),
              u.frequency(n) * u.axis(n).direction(),
              static_cast<int32_t>(u.axis(n).moving() ? u.axis(n).remaining(u.now_ns()) : 0),
              u.step(n),
              u.error(n),
              u.busy(n),
              u.program_running(n),
              u.finished(n)};
    }
    return 0;
  });
  sensor_msgs::JointState js;
  js.header.stamp = stamp;
  js.header.frame_id = frame_id_;
  std::vector<AxisStatus> st;
  for (size_t i = 0; i < axes_.size(); ++i) {
    const AxisRos& a = *axes_[i];
    AxisStatus s;
    s.header = js.header;
    s.name = a.name;
    s.number = static_cast<uint8_t>(a.n);
    s.pulses = r[i].pulses;
    s.position = static_cast<double>(s.pulses) * a.upp;
    s.frequency = r[i].frequency;
    s.remaining = r[i].remaining;
    s.step = r[i].step;
    s.busy = r[i].busy;
    s.running = r[i].running;
    s.finished = r[i].finished;
    s.error = r[i].error;
    st.push_back(s);
    js.name.push_back(a.name);
    js.position.push_back(static_cast<double>(s.pulses) * a.si);
    js.velocity.push_back(s.frequency * a.si);
  }
  joints_pub_.publish(js);
  for (size_t i = 0; i < axes_.size(); ++i) axes_[i]->status_pub.publish(st[i]);
}

}  // namespace plc_cell
