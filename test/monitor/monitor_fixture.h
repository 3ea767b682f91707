#pragma once
// A real monitor server on 127.0.0.1 (a free port) over a Plc whose scans the test drives
// itself on the virtual clock.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <string>
#include <sys/stat.h>
#include <unistd.h>

#include "client.h"
#include "plc_cell/config/cell_config.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/live_source.h"

namespace plc_cell {
namespace monitor_test {

// Two networks: a start/stop latch of Y0 and a move into R0 while Y0 is on.
constexpr const char* kProgram =
    "ORG X0\n"
    "OR Y0\n"
    "AND NOT X1\n"
    "OUT Y0\n"
    "ORG Y0\n"
    "MOV S=7 D=R0\n"
    "END\n";

// The next frame at or after scan n (frames come at the page's rate; scans are the test's).
inline nlohmann::json frame_at(WsClient& page, uint64_t n) {
  for (int i = 0; i < 100; ++i) {
    auto f = page.next("frame");
    if (f.is_null() || f["scan"].get<uint64_t>() >= n) return f;
  }
  return nullptr;
}

// How many elements and wires of a frame's networks it draws carrying power.
inline size_t energised(const nlohmann::json& frame) {
  size_t n = 0;
  for (const auto& net : frame["flow"]) n += net["on"].size();
  return n;
}

class MonitorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char tmpl[] = "/tmp/monitor_assets_XXXXXX";
    assets_ = ::mkdtemp(tmpl);
    std::ofstream(assets_ + "/index.html") << "<html>monitor</html>";
    ::mkdir((assets_ + "/js").c_str(), 0755);
    std::ofstream(assets_ + "/js/app.js") << "let x = 1;";
    plc.load_program_text(kProgram, "belt.il");
    plc.set_mode(RunMode::Run);
  }
  void TearDown() override {
    if (server) server->stop();
    std::remove((assets_ + "/js/app.js").c_str());
    ::rmdir((assets_ + "/js").c_str());
    std::remove((assets_ + "/index.html").c_str());
    ::rmdir(assets_.c_str());
  }
  // Starts the server; call after changing settings (and config.signals, the names).
  void serve() {
    settings.endpoint = "127.0.0.1:0";
    settings.asset_root = assets_;
    ServerContext context(plc);
    context.config = &config;
    source = std::make_unique<monitor::LiveSource>(context, "cell test");
    server = std::make_unique<monitor::HttpServer>(*source, settings);
    server->start();
    port = server->port();
  }
  void scan() { plc.scan(t_us += 1000); }
  std::string token() { return http_get(port, "/api/session").json().value("token", ""); }

  Plc plc;
  CellConfig config;
  monitor::HttpSettings settings;
  std::unique_ptr<monitor::LiveSource> source;
  std::unique_ptr<monitor::HttpServer> server;
  uint16_t port = 0;
  uint64_t t_us = 0;
  std::string assets_;
};

}  // namespace monitor_test
}  // namespace plc_cell
