// The `http` server kind: servers.http in the cell YAML (checked with the file's other
// errors, at file:line), the cell's LiveSource behind it, and `plc_cell run --http-tcp`.
#include <gtest/gtest.h>

#include <fstream>

#include "../reliability/run_child.h"
#include "../reliability/temp_dir.h"
#include "client.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"

namespace plc_cell {
namespace monitor_test {
namespace {

struct Files {
  TempDir dir;
  std::string yaml(const std::string& text) {
    std::ofstream(dir.path() + "/p.il") << "; the belt\nORG X0\nOUT Y0\nEND\n";
    std::ofstream(dir.path() + "/cell.yaml") << "cell: {name: belt, program: p.il}\nsignals: {start: X0, belt: Y0}\n"
                                             << text;
    return dir.path() + "/cell.yaml";
  }
};

TEST(HttpKind, YamlErrorsNameTheKeyAtItsLine) {
  Files f;
  const std::string cfg =
      f.yaml("servers:\n  http:\n    tcp: '127.0.0.1:0'\n    writable: D0-Q9\n    max_connections: 0\n");
  try {
    Cell c(cfg, {}, Cell::Purpose::Check);
    FAIL() << "accepted";
  } catch (const SourceError& e) {
    ASSERT_GE(e.diagnostics().size(), 1u) << e.what();
    const auto& d = e.diagnostics()[0];
    EXPECT_NE(d.message.find("servers.http."), std::string::npos) << e.what();
    EXPECT_GE(d.where.line, 6) << e.what();
    EXPECT_NE(std::string(e.what()).find("cell.yaml:"), std::string::npos) << e.what();
  }
}

TEST(HttpKind, OffByDefaultReadOnlyWhenOn) {
  Files f;
  {
    Cell c(f.yaml(""), {}, Cell::Purpose::Check);
    for (const auto& s : c.servers()) EXPECT_EQ(s->describe().find("monitor"), std::string::npos);
  }
  Cell c(f.yaml("servers:\n  http: {tcp: '127.0.0.1:0'}\n"), {}, Cell::Purpose::Serve);
  ASSERT_EQ(c.servers().size(), 1u);
  c.start_servers();
  const uint16_t port = uint16_t(std::stoi(c.servers()[0]->describe().substr(c.servers()[0]->describe().rfind(':') + 1)));
  const auto s = http_get(port, "/api/session").json();
  EXPECT_EQ(s["writable"], "none");
  EXPECT_EQ(s["source"], "cell belt");
  // The cell's signal names read as addresses.
  c.plc().write(parse_address("Y0"), {1});
  const auto r = http_get(port, "/api/read?a=belt,start").json();
  EXPECT_EQ(r["values"]["belt"], 1);
  EXPECT_EQ(r["values"]["start"], 0);
  // The cell's servers are in the status, this one among them.
  const auto st = http_get(port, "/api/status").json();
  ASSERT_EQ(st["servers"].size(), 1u);
  EXPECT_EQ(st["servers"][0]["name"], c.servers()[0]->describe());
  EXPECT_TRUE(st["servers"][0]["running"]);
  c.stop();
}

TEST(HttpKind, OverridesAreCheckedWithTheirOrigin) {
  Files f;
  CellOverrides o;
  o.servers.push_back({"http", "writable", {"D0-Z9"}, "--http-writable"});
  try {
    Cell c(f.yaml(""), o, Cell::Purpose::Check);
    FAIL() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("--http-writable D0-Z9"), std::string::npos) << e.what();
  }
}

TEST(HttpKind, PlcCellRunServesTheStatus) {
  Files f;
  RunChild run({"--config", f.yaml(""), "--http-tcp", "127.0.0.1:0"});
  ASSERT_EQ(run.ports.size(), 1u) << run.log;
  EXPECT_NE(run.log.find("serving monitor http://127.0.0.1:"), std::string::npos) << run.log;
  const auto r = http_get(uint16_t(run.ports[0]), "/api/status");
  ASSERT_EQ(r.status, 200) << run.log;
  EXPECT_EQ(r.json()["mode"], "run");
  EXPECT_EQ(http_get(uint16_t(run.ports[0]), "/api/ladder").json()["networks"].size(), 1u);
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
