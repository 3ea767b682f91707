// plc_cell/MonitorNodelet (docs/nodelets.md, "One monitor for the process"): one browser
// monitor for every plc_node nodelet of its manager, on ~http_tcp, with an overview of the
// cells and each cell's page at /cell/NAME/ (NAME: the cell's namespace, as cell_3). It
// serves the process's cell directory: when a cell comes or goes (a nodelet loaded,
// unloaded, ~reset), the server starts again with the cells there are, on the same port,
// and the open pages reconnect by themselves.
#include <algorithm>
#include <cctype>
#include <memory>
#include <mutex>

#include <nodelet/nodelet.h>
#include <pluginlib/class_list_macros.hpp>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/live_source.h"
#include "plc_cell/monitor/server_kind.h"
#include "plc_cell/ros/cell_directory.h"
#include "plc_cell/ros/server_params.h"

namespace plc_cell {
namespace {

// cell_2 before cell_10: the overview lists the cells by name, numbers as numbers, whatever
// order the nodelets were loaded in.
bool name_before(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) && std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      const std::string x = a.substr(i, ei - i), y = b.substr(j, ej - j);
      if (x.size() != y.size()) return x.size() < y.size();
      if (x != y) return x < y;
      i = ei;
      j = ej;
    } else if (a[i] != b[j]) {
      return a[i] < b[j];
    } else {
      ++i;
      ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

}  // namespace

class MonitorNodelet : public nodelet::Nodelet {
 public:
  ~MonitorNodelet() override {
    if (watch_) CellDirectory::process().unwatch(watch_);
    std::lock_guard<std::mutex> lk(mu_);
    if (server_) server_->stop();
  }

 private:
  void onInit() override {
    try {
      std::vector<SettingOverride> http;
      for (const auto& s : cell_overrides(getPrivateNodeHandle()).servers)
        if (s.kind == "http") http.push_back(s);
      settings_ = monitor::http_settings(
          merge_server_settings({monitor::server_kind()}, CellConfig{}, http).at("http"));
      if (settings_.endpoint.empty()) throw Error("~http_tcp: the monitor's HOST:PORT is not given");
    } catch (const std::exception& e) {
      NODELET_FATAL("monitor: %s", e.what());
      throw;
    }
    watch_ = CellDirectory::process().watch([this](const std::vector<CellDirectory::Entry>& cells) { serve(cells); });
  }

  // With the directory's lock held: no cell goes while this runs.
  void serve(std::vector<CellDirectory::Entry> cells) {
    std::lock_guard<std::mutex> lk(mu_);
    if (server_) {
      server_->stop();  // nothing reads a cell that is going, from here on
      server_.reset();
    }
    if (cells.empty()) return;
    std::sort(cells.begin(), cells.end(), [](const auto& x, const auto& y) { return name_before(x.name, y.name); });
    monitor::SourceSet set;
    set.set_title("nodelet manager " + ros::this_node::getName());
    for (const auto& e : cells) {
      ServerContext context(e.cell->plc());
      context.config = &e.cell->config();
      context.extensions = &e.cell->soft().extensions();
      context.program_path = e.cell->program_path();
      context.changes = &e.cell->changes();
      try {
        set.add(e.name, std::make_unique<monitor::LiveSource>(context, "cell " + e.name));
      } catch (const std::exception& x) {
        NODELET_ERROR("monitor: %s: not shown", x.what());  // a name given twice
      }
    }
    try {
      server_ = std::make_unique<monitor::HttpServer>(std::move(set), settings_);
      server_->start();
      // Port 0 picked a port: the next start binds the same one.
      settings_.endpoint = settings_.endpoint.substr(0, settings_.endpoint.rfind(':') + 1) + std::to_string(server_->port());
      NODELET_INFO("monitor: serving %s for %zu cells", server_->describe().c_str(), cells.size());
    } catch (const std::exception& x) {
      server_.reset();
      NODELET_ERROR("monitor: %s", x.what());
    }
  }

  monitor::HttpSettings settings_;
  std::mutex mu_;
  std::unique_ptr<monitor::HttpServer> server_;
  uint64_t watch_ = 0;
};

}  // namespace plc_cell

PLUGINLIB_EXPORT_CLASS(plc_cell::MonitorNodelet, nodelet::Nodelet)
