#pragma once
// plc_node: the soft PLC on ROS. A thin layer: the Cell (runtime/cell.h) does the work,
// this class maps it to topics, services and /diagnostics.
#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_msgs/Bool.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/LoadProgram.h"
#include "plc_cell/SimulateInputs.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/memory_services.h"
#include "plc_cell/ros/topic_group.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {

class PlcNode : private MemoryAccess, private StampedInputs {
 public:
  // Reads ~cell, the cell's overrides (ros/server_params.h), ~io_rate, ~autostart and the
  // topics' parameters; throws on bad input.
  PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  ~PlcNode();

 private:
  struct Snapshot {
    uint64_t scan_us = 0;  // the scan it was taken after: the cell's time (virtual time: the clock's)
    bool run = false;
    std::vector<uint8_t> x, y, signals;
    uint64_t forced_gen = 0;  // Memory::disabled_generation(): the forced set changed
    bool operator==(const Snapshot& o) const {
      return run == o.run && x == o.x && y == o.y && signals == o.signals && forced_gen == o.forced_gen;
    }
  };

  Snapshot take_snapshot();
  void after_scan();
  void publisher_loop();
  void publish(const Snapshot& s, bool all_signals);
  void publish_clock();  // real time: ~clock
  // Virtual time (plc_node_virtual_time.cpp): scans driven by ~clock_topic.
  void start_virtual_time(ros::NodeHandle& pnh, uint64_t period_us);
  void on_clock(uint64_t now_us);
  void on_stamped_input(uint32_t x, uint64_t stamp_us, bool v);
  // ~virtual_time/scanned (virtual_mu_ held): how far the scans got, and what was published.
  void publish_progress();
  // ~reset: a fresh cell from the same files, in virtual time.
  bool on_reset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_persist(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_servers(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_forced(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void publish_forced(const ros::Time& stamp);

  // ~read, ~write, ~force, ~release on the cell (ros/memory_services.h).
  Address resolve(const std::string& text) const override;
  std::vector<uint32_t> read(const Address& start, uint32_t count) override;
  void write(const Address& start, const std::vector<uint32_t>& raw) override;
  void force(const Address& bit, bool value) override;
  std::vector<Address> release(const Address* bit) override;
  bool on_run(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool on_load(LoadProgram::Request& req, LoadProgram::Response& res);
  // ~simulate (simulated_inputs.cpp): inputs back to the cell's simulation.
  bool on_simulate(SimulateInputs::Request& req, SimulateInputs::Response& res);

  std::unique_ptr<Cell> cell_;  // the PLC, its servers, store and scan loop
  std::string cell_path_;       // ~cell and the overrides it was built with: ~reset builds
  CellOverrides overrides_;     // the same cell again
  bool autostart_ = true;
  std::vector<std::string> extension_diagnostics_;  // their entries hold references into cell_
  // Counters (with their services), axes (services, action), ~registers/<group> and
  // temperatures (~set_pid_loop): the topics read from the cell at a rate. Before the
  // timers, subscriptions and updater_ that call into the groups: destroyed after them.
  TopicGroups topic_groups_;
  std::mutex path_mu_;
  std::string program_path_;
  std::string frame_id_;  // ~frame_id of every header

  ros::Publisher io_pub_;
  ros::Publisher io_words_pub_;  // ~io_words: the same image as 16-bit words, with every ~io
  ros::Publisher forced_pub_;  // ~forced, latched
  std::mutex forced_mu_;
  std::vector<std::pair<std::string, bool>> forced_;  // as last published
  std::vector<ros::Publisher> signal_pubs_;
  std::vector<ros::Subscriber> input_subs_;
  std::vector<ros::Publisher> stamped_pubs_;  // plc_cell/Signal, beside signal_pubs_

  // Virtual time: inputs wait in pending_ until the scan at or after their stamp.
  struct PendingInput {
    uint64_t stamp_us;
    uint64_t seq;  // arrival order breaks ties
    uint32_t x;
    bool v;
    std::function<void(ScanEngine&)> change;  // set: an extension's topic input, not an X
    bool resume = false;  // ~simulate: x goes back to the cell's simulation
  };
  // An extension's topic input (ros/extension_ros.h), as the stamped inputs.
  void apply_at(uint64_t stamp_us, std::function<void(ScanEngine&)> change) override;
  void apply(ScanEngine& e, const PendingInput& in);  // PLC lock held
  bool virtual_time_ = false;
  bool every_scan_ = false;  // ~publish_every_scan: the rate topics at every scan
  uint64_t period_us_ = 1000, lag_us_ = 0, next_scan_us_ = 0, input_seq_ = 0, late_inputs_ = 0;
  // ~virtual_time/scanned: since the start or the last ~reset.
  uint64_t scans_ = 0, last_scan_us_ = 0, inputs_received_ = 0;
  uint32_t resets_ = 0;
  // The cell's own time (what its simulation, timers and counters see) starts at 0 at the
  // first clock message (after ~reset: at the first scan of the next one): epoch_us_ is
  // that instant's clock time. Stamps stay the clock's.
  bool clock_started_ = false;
  bool after_reset_ = false;
  uint64_t epoch_us_ = 0;
  // Messages published on ~io, ~forced, ~signals/<name> and ~signals_stamped/<name>, in
  // that order (the signals in the config's order).
  std::vector<uint64_t> published_;
  ros::Publisher scanned_pub_;
  std::mutex virtual_mu_;
  std::vector<PendingInput> pending_;
  ros::Subscriber clock_sub_;
  Snapshot virtual_last_;
  bool virtual_published_ = false;
  std::vector<ros::ServiceServer> services_;
  // Real time: ~clock, the wall-clock time of the cell's time 0 (set at the first scan)
  // and then of its scans.
  ros::Publisher clock_pub_;
  std::atomic<int64_t> origin_ns_{-1};
  bool clock_sent_ = false;  // the timer's thread only
  ros::Timer io_timer_, diag_timer_, clock_timer_;
  ros::WallTime started_;
  diagnostic_updater::Updater updater_;

  std::mutex snap_mu_;
  std::condition_variable snap_cv_;
  Snapshot last_scan_, last_published_;
  bool dirty_ = false;
  bool published_once_ = false;
  bool stopping_ = false;
  std::thread publisher_;
};

}  // namespace plc_cell
