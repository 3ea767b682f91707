// scenario_runner: a scenario file's test cases as gtest tests on a running plc_node, one
// test per case, registered at run time, so that rostest's --gtest_output=xml gives a JUnit
// result per case. The cases run with the runner of `plc_cell test` (scenario/runner.h) on
// plc_node through its topics (ros/scenario_ros_target.h), each on a fresh cell (~reset).
//
// Parameters: ~scenario (file), ~node (plc_node's name, default plc_node, resolved in this
// node's namespace), ~case (only the case of this name, or its rows "NAME[...]"), ~timeout
// (s, default 10: the longest one scan may take to come back), ~read_fallback (default
// true: an address on no topic is read with ~read; false: such a case fails its check).
// ~real_time (default false): the cases run in wall-clock time on plc_node in real time or
// on fatek_bridge / tri_bridge (ros/scenario_real_time.h), ~tolerance (s, default 0) the
// most a window tighter than the resolution is widened. A scenario file that names a line
// runs on the line's cells at ~line_ns/<cell>/plc_node (~line_ns default: /<the line's
// name>): in virtual time on the line nodelet's one clock (ros/scenario_line_link.h), or in
// real time (ros/scenario_line_real_time.h).
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <atomic>
#include <climits>
#include <csignal>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>

#include "plc_cell/core/error.h"
#include "plc_cell/line/line_file.h"
#include "plc_cell/ros/scenario_line_link.h"
#include "plc_cell/ros/scenario_line_real_time.h"
#include "plc_cell/ros/scenario_real_time.h"
#include "plc_cell/ros/scenario_ros_target.h"
#include "plc_cell/ros/server_params.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/runner.h"
#include "plc_cell/scenario/scenario_file.h"

namespace {

using plc_cell::Cell;
using plc_cell::CellOverrides;
using plc_cell::Error;
namespace sc = plc_cell::scenario;

std::string real(const std::string& path) {
  char buf[PATH_MAX];
  return ::realpath(path.c_str(), buf) ? std::string(buf) : path;
}

// SIGINT or SIGTERM, once one has come: in real time the case ends there and the PLC is put
// back before the runner goes (in virtual time, ROS shuts down as usual).
std::atomic<int> g_stop{0};
bool g_real_time = false;

void on_signal(int signo) {
  g_stop = signo;
  if (!g_real_time) ros::requestShutdown();
}

// What the cases share: the scenario, and the connection to plc_node.
struct Shared {
  std::string error;  // why nothing can run (a bad file, the wrong cell on plc_node)
  sc::Scenario scenario;
  std::unique_ptr<sc::NodeLink> link;
  std::unique_ptr<plc_cell::line::Line> line;  // virtual time: the scenario's line, checked
  std::unique_ptr<sc::LineLink> line_link;     // virtual time: the run on the line's nodes
  std::unique_ptr<Cell> cell;                 // real time: the scenario's cell, checked
  std::unique_ptr<sc::RealTimeCases> real_time;  // real time: the run on the node or the line
};

class CaseTest : public testing::Test {
 public:
  CaseTest(Shared* run, const sc::Case* c) : run_(run), case_(c) {}

  void TestBody() override {
    if (!run_->error.empty()) FAIL() << run_->error;
    if (run_->real_time) return real_time();
    try {
      std::unique_ptr<sc::Target> made;
      if (run_->line_link) {
        run_->line_link->connect();
        made = std::make_unique<sc::LineRosTarget>(*run_->line_link);
      } else {
        run_->link->connect();
        made = std::make_unique<sc::RosTarget>(*run_->link);
      }
      sc::Target& target = *made;
      const auto errors = sc::check_case(*case_, target);
      if (!errors.empty()) {
        std::string all;
        for (const auto& e : errors) all += e.to_string() + "\n";
        ADD_FAILURE_AT(case_->file.c_str(), case_->line) << "this case cannot run on plc_node:\n" << all;
        return;
      }
      const sc::CaseResult r = sc::run_case(*case_, target);
      RecordProperty("virtual_time", sc::format_time(r.virtual_us));
      RecordProperty("scans", std::to_string(r.scans));
      if (!r.passed) ADD_FAILURE_AT(case_->file.c_str(), case_->line) << r.failure << "\n" << r.details;
    } catch (const std::exception& e) {
      FAIL() << e.what();
    }
  }

 private:
  // The case in wall-clock time; refused whole when any case of the file is (nothing was
  // written), and failed when the PLC could not be put back as found.
  void real_time() {
    sc::RealTimeCases& rt = *run_->real_time;
    RecordProperty("target", rt.target());
    RecordProperty("resolution", rt.resolution().text());
    if (!rt.refusals().empty()) {
      ADD_FAILURE_AT(case_->file.c_str(), case_->line) << "refused on " << rt.target() << ", nothing was written:\n"
                                                       << rt.refusals();
      return;
    }
    if (g_stop) {
      ADD_FAILURE_AT(case_->file.c_str(), case_->line) << "not run: the runner was stopped";
      return;
    }
    const sc::RealTimeOutcome o = rt.run(*case_);
    RecordProperty("polls", std::to_string(o.polls));
    if (!o.result.passed) ADD_FAILURE_AT(case_->file.c_str(), case_->line) << o.result.failure << "\n" << o.result.details;
    for (const auto& r : o.restore.restored) std::cout << "restored as found: " << r << "\n";
    std::string missing;
    for (const auto& r : o.restore.not_restored) missing += "NOT RESTORED: " + r + "\n";
    if (!missing.empty()) ADD_FAILURE_AT(case_->file.c_str(), case_->line) << "the PLC is not as it was found:\n" << missing;
  }

  Shared* run_;
  const sc::Case* case_;
};

// In real time, after every case: the points the cases touch forced as before the first.
class LeftAsFound : public testing::Test {
 public:
  explicit LeftAsFound(Shared* run) : run_(run) {}
  void TestBody() override {
    std::string wrong;
    for (const auto& w : run_->real_time->not_as_found()) wrong += w + "\n";
    EXPECT_TRUE(wrong.empty()) << "after the cases, on " << run_->real_time->target() << ":\n" << wrong;
  }

 private:
  Shared* run_;
};

std::string suite_name(const std::string& file) {
  std::string base = file.substr(file.rfind('/') + 1);
  for (const char* ext : {".scenario.yaml", ".yaml", ".yml"}) {
    const std::string e(ext);
    if (base.size() > e.size() && base.compare(base.size() - e.size(), e.size(), e) == 0) {
      base.resize(base.size() - e.size());
      break;
    }
  }
  for (char& ch : base)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  return base.empty() ? "scenario" : base;
}

// Where the scenario's line runs: ~line_ns, else /<the line file's name>.
std::string line_namespace(const sc::Scenario& scenario, const std::string& line_ns) {
  if (!line_ns.empty()) return ros::names::resolve(line_ns);
  return "/" + plc_cell::line::load_line_file(scenario.line).name;
}

// Loads the scenario and checks that plc_node runs its cell (or the line nodelet its line), in
// virtual time.
void prepare(Shared* run, const std::string& file, const std::string& node, const std::string& line_ns,
             double timeout_s, bool read_fallback) {
  if (file.empty()) throw Error("~scenario is not set: give the scenario file");
  run->scenario = sc::load_scenario(file);
  if (!run->scenario.line.empty()) {
    plc_cell::line::LineOptions lo;
    lo.purpose = Cell::Purpose::Check;
    run->line = std::make_unique<plc_cell::line::Line>(run->scenario.line, lo);
    run->line_link = std::make_unique<sc::LineLink>(*run->line, line_namespace(run->scenario, line_ns), timeout_s,
                                                     read_fallback);
    return;
  }
  std::string node_cell;
  if (!ros::param::get(node + "/cell", node_cell))
    throw Error("no parameter " + node + "/cell: is ~node (" + node + ") plc_node's name?");
  bool virtual_time = false;
  ros::param::get(node + "/virtual_time", virtual_time);
  if (!virtual_time) throw Error(node + " runs in real time: a scenario needs ~virtual_time: true");
  // The cell as plc_node builds it (same files, same parameters), and as the scenario names it.
  const CellOverrides node_overrides = plc_cell::cell_overrides(ros::NodeHandle(node));
  Cell on_node(node_cell, node_overrides, Cell::Purpose::Check);
  CellOverrides mine;
  mine.program = run->scenario.program;
  Cell named(run->scenario.cell, mine, Cell::Purpose::Check);
  if (real(node_cell) != real(run->scenario.cell))
    throw Error(node + " runs the cell " + node_cell + ", the scenario names " + run->scenario.cell);
  if (real(on_node.program_path()) != real(named.program_path()))
    throw Error(node + " runs the program " + on_node.program_path() + ", the scenario's cell runs " +
                named.program_path());
  double lag = 0.1;
  ros::param::get(node + "/virtual_time_lag", lag);
  run->link = std::make_unique<sc::NodeLink>(node, on_node.config(), on_node.scan_period_us(), uint64_t(lag * 1e6),
                                             timeout_s, read_fallback);
}

// What runs at ~node: plc_node (its ~cell), fatek_bridge (~station) or tri_bridge (~id).
std::string node_kind(const std::string& node) {
  if (ros::param::has(node + "/cell")) return "plc_node";
  if (ros::param::has(node + "/station")) return "fatek_bridge";
  if (ros::param::has(node + "/id")) return "tri_bridge";
  throw Error("cannot tell what " + node + " is (no ~cell, ~station or ~id parameter): is ~node the name of "
              "plc_node, fatek_bridge or tri_bridge?");
}

// Loads the scenario and connects to the node (or the line's nodes), in wall-clock time.
void prepare_real_time(Shared* run, const std::string& file, const std::string& node, const std::string& line_ns,
                       double timeout_s, double tolerance_s) {
  if (file.empty()) throw Error("~scenario is not set: give the scenario file");
  run->scenario = sc::load_scenario(file);
  if (!run->scenario.line.empty()) {
    run->real_time = std::make_unique<sc::LineRealTimeRun>(run->scenario, line_namespace(run->scenario, line_ns),
                                                            timeout_s, uint64_t(tolerance_s * 1e6), &g_stop);
    return;
  }
  const std::string kind = node_kind(node);
  if (kind == "plc_node") {
    bool virtual_time = false;
    ros::param::get(node + "/virtual_time", virtual_time);
    if (virtual_time) throw Error(node + " runs in virtual time: ~real_time needs it in real time");
    std::string node_cell;
    ros::param::get(node + "/cell", node_cell);
    if (real(node_cell) != real(run->scenario.cell))
      throw Error(node + " runs the cell " + node_cell + ", the scenario names " + run->scenario.cell);
  }
  CellOverrides mine;
  mine.program = run->scenario.program;
  run->cell = std::make_unique<Cell>(run->scenario.cell, mine, Cell::Purpose::Check);
  run->real_time = std::make_unique<sc::RealTimeRun>(run->scenario, run->cell->config(), run->cell->scan_period_us(),
                                                      node, kind, timeout_s, uint64_t(tolerance_s * 1e6), &g_stop);
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "scenario_runner", ros::init_options::AnonymousName | ros::init_options::NoSigintHandler);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  ros::NodeHandle pnh("~");
  std::string file, node = "plc_node", only, line_ns;
  double timeout_s = 10, tolerance_s = 0;
  bool read_fallback = true;
  pnh.param("real_time", g_real_time, g_real_time);
  pnh.param("tolerance", tolerance_s, tolerance_s);
  pnh.param<std::string>("scenario", file, file);
  pnh.param<std::string>("node", node, node);
  pnh.param<std::string>("case", only, only);
  pnh.param<std::string>("line_ns", line_ns, line_ns);
  pnh.param("timeout", timeout_s, timeout_s);
  pnh.param("read_fallback", read_fallback, read_fallback);
  node = ros::names::resolve(node);

  static Shared run;
  try {
    if (g_real_time)
      prepare_real_time(&run, file, node, line_ns, timeout_s, tolerance_s);
    else
      prepare(&run, file, node, line_ns, timeout_s, read_fallback);
  } catch (const std::exception& e) {
    run.error = e.what();
  }
  // In real time the suite names its target: "conveyor_hardware_on_ros_scenario_plc_node".
  std::string suite = suite_name(file);
  // (the target is "ros:" and the node's name, or the line's namespace).
  if (g_real_time) suite += "_on_ros" + (run.real_time ? run.real_time->target().substr(4) : node);
  for (char& ch : suite)
    if (!isalnum(static_cast<unsigned char>(ch))) ch = '_';
  if (!run.error.empty()) {  // one failing test that says why
    testing::RegisterTest(suite.c_str(), "setup", nullptr, nullptr, __FILE__, __LINE__,
                          []() -> testing::Test* { return new CaseTest(&run, nullptr); });
    return RUN_ALL_TESTS();
  }
  size_t registered = 0;
  for (const sc::Case& c : run.scenario.cases) {
    if (!only.empty() && c.name != only && c.name.compare(0, only.size() + 1, only + "[") != 0) continue;
    const sc::Case* cp = &c;
    testing::RegisterTest(suite.c_str(), c.name.c_str(), nullptr, nullptr, c.file.c_str(), c.line,
                          [cp]() -> testing::Test* { return new CaseTest(&run, cp); });
    ++registered;
  }
  if (!registered) {
    run.error = only.empty() ? file + " has no test case" : file + " has no case named '" + only + "'";
    testing::RegisterTest(suite.c_str(), "setup", nullptr, nullptr, __FILE__, __LINE__,
                          []() -> testing::Test* { return new CaseTest(&run, nullptr); });
  }
  // Last: the whole run left no force behind, where the node says which points are forced.
  if (g_real_time && run.error.empty() && registered && run.real_time->says_forced())
    testing::RegisterTest(suite.c_str(), "the PLC is as it was found", nullptr, nullptr, __FILE__, __LINE__,
                          []() -> testing::Test* { return new LeftAsFound(&run); });
  const int rc = RUN_ALL_TESTS();
  run.real_time.reset();
  run.link.reset();
  run.line_link.reset();
  ros::shutdown();
  return rc;
}
