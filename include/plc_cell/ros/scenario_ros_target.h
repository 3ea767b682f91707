#pragma once
// plc_node as a scenario target (scenario/target.h), through the topics and services a robot
// stack uses: the scenario_runner rostest node runs a scenario file's cases on it with the
// same runner as `plc_cell test` (docs/testing-your-cell.md, "The same scenarios as
// rostests"). plc_node runs in virtual time (~virtual_time: true): each scan is one clock
// message, and ~virtual_time/scanned says when every message of the scan has arrived.
#include <condition_variable>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "plc_cell/IoState.h"
#include "plc_cell/RegisterBlock.h"
#include "plc_cell/ScanProgress.h"
#include "plc_cell/Signal.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/ros/topic_probes.h"
#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace scenario {

// The connection to one plc_node, shared by every case of a run: its subscriptions stay
// connected from case to case (each case starts with ~reset). What an extension's probes
// read, its registered TopicProbes subscribe through it (ros/topic_probes.h).
class NodeLink : public TopicFeed {
 public:
  // node: plc_node's resolved name ("/plc_node", "/cell_a/plc_node"); config: the cell it
  // runs (read by the caller from the same files); period_us, lag_us: its scan period and
  // ~virtual_time_lag. timeout_s bounds every wait. read_fallback: an address on no topic
  // is read with ~read (else check() refuses it).
  NodeLink(const std::string& node, const CellConfig& config, uint64_t period_us, uint64_t lag_us, double timeout_s,
           bool read_fallback);
  ~NodeLink();

  // Once, before the first case: waits until plc_node hears the clock and the inputs and
  // until every topic of a scan reaches this node. Throws Error saying what did not come.
  void connect();

  // TopicFeed, for the extensions' TopicProbes.
  const std::string& node() const override { return node_; }
  ros::NodeHandle& handle() override { return nh_; }
  void received(const std::string& topic, uint64_t stamp_ns, const std::function<void()>& store) override;
  ros::Publisher advertise(ros::AdvertiseOptions options) override;
  void connect_publisher(ros::Publisher* pub, const std::string& what) override;
  ros::Time next_input_stamp() override;

 private:
  friend class RosTarget;
  friend class LineLink;
  struct Latest;  // the last message of each topic this case

  // The pieces of connect(), begin_case() and scan() that a line's link (scenario_line_link.h)
  // runs on each of its cells around the line's one clock and reset.
  void advertise_inputs();  // ~inputs_stamped/<name> and the progress
  // A case's time 0 as a stamp; counted: a reset of a connected link, whose progress follows.
  void start_case(uint64_t t0_us, bool counted);
  uint64_t next_t0() const;  // where the next case may start, every earlier stamp behind it
  bool take_topics(double timeout_s);
  bool await_first_scan(double timeout_s);  // a case's scan at 0 and all of its messages
  void mark_connected();
  std::string missing();  // what of a scan has not arrived
  void await_inputs();
  void await_scan(uint64_t t_us);
  void stepped(uint64_t t_us);  // the runner's step t_us is done

  // A fresh cell (~reset) whose scans are stamped from t0 on.
  void begin_case();
  void scan(uint64_t t_us);
  // Waits until pred holds on the latest ScanProgress of this case; throws Error naming what.
  template <class Pred>
  bool wait(Pred pred, double timeout_s);
  void subscribe(const std::string& topic);
  template <class M, class Store>
  ros::Subscriber keep(const std::string& topic, Store store);
  template <class M>
  ros::Publisher advertise(const std::string& topic);
  void publish_clock(uint64_t t_us);
  bool scan_complete(uint64_t t_us) const;  // mu_ held
  void call_reset();
  void clear_case();  // mu_ held: no message of the new case yet
  // The registered side that reads p's family, or nullptr.
  TopicProbes* probes_of(const Probe& p) const;
  uint32_t read_memory(const std::string& name);  // ~read, once per scan

  std::string node_;
  CellConfig config_;
  uint64_t period_us_;
  uint64_t step_us_;  // the runner's steps: the node's period, or the line's tick for a cell of a line
  uint64_t lag_us_;
  double timeout_s_;
  bool read_fallback_;
  ros::ServiceClient read_client_;
  std::map<std::string, uint32_t> read_cache_;  // this scan's ~read values
  ros::NodeHandle nh_;
  ros::CallbackQueue queue_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::Publisher clock_pub_;
  std::map<uint32_t, ros::Publisher> input_pubs_;  // X index -> ~inputs_stamped/<name>
  std::vector<std::unique_ptr<TopicProbes>> probes_;  // every registered extension's
  std::vector<ros::Subscriber> subs_;
  ros::Subscriber progress_sub_;
  std::vector<std::string> topics_;  // every topic subscribed (resolved)

  mutable std::mutex mu_;
  std::condition_variable cv_;
  bool connected_ = false;
  uint64_t t0_us_ = 0;       // this case's time 0 as a stamp
  uint64_t next_t0_us_ = 1000000000;  // 1000 s: later cases start after every earlier stamp
  uint32_t resets_ = 0;      // ~reset calls plc_node has served, once known
  bool resets_known_ = false;
  uint64_t inputs_sent_ = 0;
  bool scanned_ = false;     // this case has scanned at least once
  uint64_t last_t_us_ = 0;
  ScanProgress progress_;    // the latest of this case
  bool have_progress_ = false;
  std::map<std::string, uint64_t> received_;  // per topic, stamped at or after t0
  std::unique_ptr<Latest> latest_;
};

// The last message of each topic this case.
struct NodeLink::Latest {
  IoState io;
  bool have_io = false;
  std::map<std::string, bool> signals;  // by topic
  std::map<std::string, RegisterBlock> registers;
};

// One case: a fresh cell on plc_node (its constructor calls ~reset).
class RosTarget : public Target {
 public:
  explicit RosTarget(NodeLink& link, bool begin_case = true);  // false: a cell of a line's case

  uint64_t period_us() const override { return link_.period_us_; }
  void scan(uint64_t t_us) override { link_.scan(t_us); }
  std::string check(const Probe& p, bool writing) override;
  std::string label(const Probe& p) override { return probe_label(p, link_.config_); }
  Reading read(const Probe& p) override;
  void set(const Probe& p, const Value& v) override;
  void write(const Probe& p, const Value& v) override;
  void force(const Probe& p, bool on) override;
  void release(const Probe* p) override;
  void simulate(const Probe* p) override;
  std::string fault() override;

 private:
  // Where an address's value is published: "" if on no topic.
  std::string topic_of(const Address& a) const;
  bool has_topic(const std::string& private_name) const;

  NodeLink& link_;
};

}  // namespace scenario
}  // namespace plc_cell
