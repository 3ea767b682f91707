#include "plc_cell/ros/fatek_bridge.h"

#include "plc_cell/core/error.h"

namespace plc_cell {

FatekBridge::FatekBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh, pnh.getNamespace()) {
  const LinkParams lp = read_link_params(pnh, 9600, "7E1");
  int station = 1;
  pnh.param("station", station, station);
  if (station < 1 || station > 254) throw Error("~station must be 1..254");

  fatek::BridgeConfig cfg = bridge_config(lp, &fatek::load_bridge_config);
  cfg.station = station;
  topics_ = std::make_unique<BridgeTopics>(pnh, cfg.signals, cfg.groups);
  bridge_ = std::make_unique<fatek::Bridge>(std::move(cfg), topics_->sinks<fatek::Bridge::Sinks>("fatek_bridge"));

  services_ = advertise_memory_services(pnh, *this);
  for (auto& s : advertise_link_services(pnh, *bridge_, [this](bool run) { bridge_->set_run(run); }))
    services_.push_back(s);
  updater_.add("link", this, &FatekBridge::diagnose);
  diag_timer_ = start_diagnostics(nh, updater_, "fatek/" + bridge_->describe());
  bridge_->start();
  ROS_INFO("fatek_bridge: %s, %zu group(s), %zu signal(s), I/O image %zu frame(s) per poll",
           bridge_->describe().c_str(), bridge_->config().groups.size(), bridge_->config().signals.size(),
           bridge_->io_frames());
}

FatekBridge::~FatekBridge() {
  if (bridge_) bridge_->stop();  // before the publishers its sinks reach go
}

void FatekBridge::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) { diagnose_link(stat, *bridge_); }

}  // namespace plc_cell
