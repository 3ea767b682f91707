// plc_node on /diagnostics: the scan, the forced points, the store and the servers (each
// extension's entries are added from the cell's extensions, ros/extension_diagnostics.h).
#include <unistd.h>

#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

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
  stat.add("overruns, thread off the CPU", v.st.overruns_off_cpu);
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

// A forced input or output looks like any other state in ~io: a cell that stops "for no
// reason" is often one a client locked. The list is a WARN here so that it shows.
void PlcNode::diagnose_forced(diagnostic_updater::DiagnosticStatusWrapper& stat) {
  std::lock_guard<std::mutex> lk(shown_mu_);
  const auto& forced = shown_->forced;
  if (forced.empty()) {
    stat.summary(diagnostic_msgs::DiagnosticStatus::OK, "no point forced");
    return;
  }
  std::string list;
  for (const auto& p : forced) {
    list += (list.empty() ? "" : ", ") + p.first + (p.second ? "=ON" : "=OFF");
    stat.add(p.first, p.second ? "forced ON" : "forced OFF");
  }
  stat.summary(diagnostic_msgs::DiagnosticStatus::WARN,
               std::to_string(forced.size()) + " forced (release with ~release): " + list);
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

}  // namespace plc_cell
