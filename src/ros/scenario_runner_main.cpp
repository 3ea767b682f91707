// scenario_runner: a scenario file's test cases as gtest tests on a running plc_node, one
// test per case, registered at run time, so that rostest's --gtest_output=xml gives a JUnit
// result per case. The cases run with the runner of `plc_cell test` (scenario/runner.h) on
// plc_node through its topics (ros/scenario_ros_target.h), each on a fresh cell (~reset).
//
// Parameters: ~scenario (file), ~node (plc_node's name, default plc_node, resolved in this
// node's namespace), ~case (only the case of this name, or its rows "NAME[...]"), ~timeout
// (s, default 10: the longest one scan may take to come back), ~read_fallback (default
// true: an address on no topic is read with ~read; false: such a case fails its check).
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <climits>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <string>

#include "plc_cell/core/error.h"
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

// What the cases share: the scenario, and the connection to plc_node.
struct Shared {
  std::string error;  // why nothing can run (a bad file, the wrong cell on plc_node)
  sc::Scenario scenario;
  std::unique_ptr<sc::NodeLink> link;
};

class CaseTest : public testing::Test {
 public:
  CaseTest(Shared* run, const sc::Case* c) : run_(run), case_(c) {}

  void TestBody() override {
    if (!run_->error.empty()) FAIL() << run_->error;
    try {
      run_->link->connect();
      sc::RosTarget target(*run_->link);
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
  Shared* run_;
  const sc::Case* case_;
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

// Loads the scenario and checks that plc_node runs its cell, in virtual time.
void prepare(Shared* run, const std::string& file, const std::string& node, double timeout_s, bool read_fallback) {
  if (file.empty()) throw Error("~scenario is not set: give the scenario file");
  run->scenario = sc::load_scenario(file);
  if (!run->scenario.line.empty())
    throw Error(file + " names a line of cells (" + run->scenario.line +
                "): this runner drives one plc_node; plc_cell test runs a line's scenarios (docs/lines.md)");
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

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "scenario_runner", ros::init_options::AnonymousName);
  ros::NodeHandle pnh("~");
  std::string file, node = "plc_node", only;
  double timeout_s = 10;
  bool read_fallback = true;
  pnh.param<std::string>("scenario", file, file);
  pnh.param<std::string>("node", node, node);
  pnh.param<std::string>("case", only, only);
  pnh.param("timeout", timeout_s, timeout_s);
  pnh.param("read_fallback", read_fallback, read_fallback);
  node = ros::names::resolve(node);

  static Shared run;
  try {
    prepare(&run, file, node, timeout_s, read_fallback);
  } catch (const std::exception& e) {
    run.error = e.what();
  }
  const std::string suite = suite_name(file);
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
  const int rc = RUN_ALL_TESTS();
  run.link.reset();
  ros::shutdown();
  return rc;
}
