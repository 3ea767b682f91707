#pragma once
// plc_node: the soft PLC on ROS. A thin layer: the Cell (runtime/cell.h) does the work,
// this class maps it to topics, services and /diagnostics. One set of topics and services,
// whichever driver scans the cell (ros/scan_driver.h: the real-time loop or virtual time).
// It builds its own cell from ~cell, or gives a cell someone else owns (a line's: ros/line_node.h)
// the same ROS side.
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>
#include <std_srvs/SetBool.h>
#include <std_srvs/Trigger.h>

#include "plc_cell/LoadProgram.h"
#include "plc_cell/SimulateInputs.h"
#include "plc_cell/ros/cell_directory.h"
#include "plc_cell/ros/extension_ros.h"
#include "plc_cell/ros/memory_services.h"
#include "plc_cell/ros/scan_driver.h"
#include "plc_cell/ros/topic_group.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {

class PlcNode : private MemoryAccess, private ScanDriver::Host, private StampedInputs {
 public:
  // Reads ~cell, the cell's overrides (ros/server_params.h), ~io_rate, ~autostart, ~virtual_time
  // and the topics' parameters; throws on bad input.
  PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);
  // The ROS side of a cell built by its owner, who keeps it (and stops it) after this node
  // goes; make_driver(host) makes the driver that scans it. Throws on bad input.
  using DriverFactory = std::function<std::unique_ptr<ScanDriver>(ScanDriver::Host&)>;
  PlcNode(ros::NodeHandle& nh, ros::NodeHandle& pnh, Cell& cell, const DriverFactory& make_driver);
  ~PlcNode() override;

  // A cell of a line whose owner built the line afresh (a line's reset in virtual time):
  // why fresh cannot take the cell's place under this node's topics ("" if it can), and the
  // swap, with no scan running; the owner stops and drops the old cell after it.
  std::string adoption_refusal(Cell& fresh);
  void adopt(Cell& fresh);

 private:
  struct Snapshot {
    uint64_t scan_us = 0;  // the cell's time of the scan it was taken after
    bool run = false;
    std::vector<uint8_t> x, y, signals;
    uint64_t forced_gen = 0;  // Memory::disabled_generation(): the forced set changed
    bool operator==(const Snapshot& o) const {
      return run == o.run && x == o.x && y == o.y && signals == o.signals && forced_gen == o.forced_gen;
    }
  };
  // What the topics of one cell showed: ~reset starts a fresh one with the fresh cell.
  struct Shown {
    explicit Shown(size_t topics) : counts(topics, 0) {}
    Snapshot pending;              // to publish; posted: a publish of it is on its way
    bool posted = false;
    Snapshot last;                 // as last published
    bool published = false;
    std::vector<uint64_t> counts;  // messages on ~io, ~forced, ~signals/*, ~signals_stamped/*
    std::vector<std::pair<std::string, bool>> forced;  // as last published
  };

  // Everything but the cell: topics, services, diagnostics, the driver; then the scans start.
  void attach(ros::NodeHandle& nh, ros::NodeHandle& pnh, const DriverFactory& make_driver);
  void make_topics(ros::NodeHandle& pnh);
  void make_diagnostics();
  std::unique_ptr<ScanDriver> make_driver(ros::NodeHandle& nh, ros::NodeHandle& pnh);

  // ScanDriver::Host.
  Cell& cell() override { return *cell_; }
  void apply(ScanEngine& e, const TimedInput& in) override;
  uint64_t scanned() override;
  void count_published(std::vector<std::string>* topics, std::vector<uint64_t>* counts) override;
  // An extension's topic input (ros/extension_ros.h), through the driver as the X inputs.
  void apply_at(uint64_t stamp_us, std::function<void(ScanEngine&)> change) override;

  // Under the PLC lock. unchanged(): whether the memory still shows `seen`, without a copy
  // or an allocation, so that a scan that changed nothing costs a compare of the points.
  Snapshot take_snapshot(const ScanEngine& e, const Memory& m) const;
  bool unchanged(const ScanEngine& e, const Memory& m, const Snapshot& seen) const;
  void publish_io();  // the pending snapshot, on the driver's publishing thread
  void publish(const Snapshot& s, const Snapshot& prev, bool all_signals);
  void publish_forced(const ros::Time& stamp);
  void input(TimedInput in) { driver_->input(in); }
  // ~reset (plc_node_reset.cpp): a fresh cell from the same files.
  bool on_reset(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // Puts cell in place of cell_ (owned: own, else its owner's); "" or why its servers failed.
  std::string swap_cell(std::unique_ptr<Cell> own, Cell& cell);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_persist(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_servers(diagnostic_updater::DiagnosticStatusWrapper& stat);
  void diagnose_forced(diagnostic_updater::DiagnosticStatusWrapper& stat);

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

  std::unique_ptr<Cell> own_cell_;  // the cell built from ~cell; none for a cell of a line
  Cell* cell_ = nullptr;           // the PLC, its servers, store and scan loop
  // cell_ in the process's cell directory (its monitor); ends before the cell does.
  std::unique_ptr<CellDirectory::Listing> listing_;
  std::string listed_as_;
  std::string cell_path_;       // ~cell and the overrides it was built with: ~reset builds
  CellOverrides overrides_;     // the same cell again
  bool autostart_ = true;
  bool every_scan_ = false;     // ~publish_every_scan: the rate topics at every scan
  std::string node_name_;       // the node's (or nodelet's) private namespace
  std::vector<std::string> extension_diagnostics_;  // their entries hold references into cell_
  // Counters (with their services), axes (services, action), ~registers/<group> and
  // temperatures (~set_pid_loop): the topics read from the cell at a rate. Before the
  // driver, subscriptions and updater_ that call into the groups: destroyed after them.
  TopicGroups topic_groups_;
  std::mutex path_mu_;
  std::string program_path_;
  std::string frame_id_;  // ~frame_id of every header

  ros::Publisher io_pub_;
  ros::Publisher io_words_pub_;  // ~io_words: the same image as 16-bit words, with every ~io
  ros::Publisher forced_pub_;    // ~forced, latched
  std::vector<ros::Publisher> signal_pubs_;
  std::vector<ros::Publisher> stamped_pubs_;  // plc_cell/Signal, beside signal_pubs_
  std::vector<ros::Subscriber> input_subs_;
  std::vector<ros::ServiceServer> services_;
  std::unique_ptr<VirtualRate> io_rate_;  // ~io again at this rate of the cell's time
  ros::Timer diag_timer_;
  ros::WallTime started_;
  diagnostic_updater::Updater updater_;

  std::mutex shown_mu_;
  std::unique_ptr<Shown> shown_;
  // The scan thread's own: the last scan's snapshot as handed to publishing (seen_any_: one
  // was); ~reset clears it between scans.
  Snapshot seen_;
  bool seen_any_ = false;
  std::mutex io_mu_;  // one ~io publish at a time, in the order of the scans
  std::unique_ptr<ScanDriver> driver_;  // last: it scans, and is stopped, first
};

}  // namespace plc_cell
