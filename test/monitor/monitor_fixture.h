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
  // Starts the server; call after changing settings.
  void serve() {
    settings.endpoint = "127.0.0.1:0";
    settings.asset_root = assets_;
    source = std::make_unique<monitor::LiveSource>(ServerContext(plc), "cell test");
    server = std::make_unique<monitor::HttpServer>(*source, settings);
    server->start();
    port = server->port();
  }
  void scan() { plc.scan(t_us += 1000); }
  std::string token() { return http_get(port, "/api/session").json().value("token", ""); }

  Plc plc;
  monitor::HttpSettings settings;
  std::unique_ptr<monitor::LiveSource> source;
  std::unique_ptr<monitor::HttpServer> server;
  uint16_t port = 0;
  uint64_t t_us = 0;
  std::string assets_;
};

}  // namespace monitor_test
}  // namespace plc_cell
