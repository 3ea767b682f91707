#include "plc_cell/ros/tri_bridge.h"

#include "plc_cell/core/error.h"

namespace plc_cell {

TriBridge::TriBridge(ros::NodeHandle& nh, ros::NodeHandle& pnh) : updater_(nh, pnh, pnh.getNamespace()) {
  const LinkParams lp = read_link_params(pnh, tri::kDefaultBaud, "8N1");
  int id = 1;
  pnh.param("id", id, id);
  if (id < 0 || id > 255) throw Error("~id must be 0..255");

  tri::BridgeConfig cfg = bridge_config(lp, &tri::load_bridge_config);
  cfg.id = id;
  topics_ = std::make_unique<BridgeTopics>(pnh, cfg.signals, cfg.groups);
  bridge_ = std::make_unique<tri::Bridge>(std::move(cfg), topics_->sinks<tri::Bridge::Sinks>("tri_bridge"));

  services_ = advertise_memory_services(pnh, *this);
  for (auto& s : advertise_link_services(pnh, *bridge_, [this](bool run) { bridge_->set_run(run); }))
    services_.push_back(s);
  updater_.add("link", this, &TriBridge::diagnose);
  diag_timer_ = start_diagnostics(nh, updater_, "tri/" + bridge_->describe());
  bridge_->start();
  ROS_INFO("tri_bridge: %s, %zu group(s), %zu signal(s), I/O image %zu frame(s) per poll",
           bridge_->describe().c_str(), bridge_->config().groups.size(), bridge_->config().signals.size(),
           bridge_->io_frames());
}

TriBridge::~TriBridge() {
  if (bridge_) bridge_->stop();  // before the publishers its sinks reach go
}

// The link, and the discretes held by ~force (the TRi has no DISABLE: a WARN while any is).
void TriBridge::diagnose(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  diagnose_link(stat, *bridge_);
  const auto forced = bridge_->forced();
  std::string list;
  for (const auto& f : forced) list += (list.empty() ? "" : ", ") + format_address(f.first) + (f.second ? " ON" : " OFF");
  stat.add("forced", list);
  if (!forced.empty()) stat.mergeSummary(diagnostic_msgs::DiagnosticStatus::WARN, "forced: " + list);
}

}  // namespace plc_cell
