// The composition root: one Cell for check, sim, run and plc_node. The server settings of
// the YAML, the command line and plc_node's parameters are one schema merged once; a
// value is checked wherever it comes from, with its origin in the message.
#include <gtest/gtest.h>

#include <fstream>

#include "../reliability/temp_dir.h"
#include "plc_cell/core/error.h"
#include "plc_cell/runtime/cell.h"

using namespace plc_cell;

namespace {

struct Files {
  TempDir dir;
  std::string yaml(const std::string& text) {
    std::ofstream(dir.path() + "/p.il") << "ORG M1925\nOUT Y0\nEND\n";
    std::ofstream(dir.path() + "/cell.yaml") << "cell: {program: p.il}\n" << text;
    return dir.path() + "/cell.yaml";
  }
};

SettingOverride over(const std::string& kind, const std::string& key, std::vector<std::string> v,
                     const std::string& origin) {
  return {kind, key, std::move(v), origin};
}

std::string error_of(const std::string& config, const CellOverrides& o, Cell::Purpose p = Cell::Purpose::Check) {
  try {
    Cell c(config, o, p);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(CellSettings, AnOverrideReplacesOnlyItsKey) {
  Files f;
  const std::string cfg = f.yaml("servers:\n  fatek: {tcp: ':0', station: 3, writable: [D0-D9]}\n");
  CellOverrides o;
  o.servers.push_back(over("fatek", "station", {"5"}, "--fatek-station"));
  Cell cell(cfg, o, Cell::Purpose::Check);
  const Settings& s = cell.server_settings().at("fatek");
  EXPECT_EQ(s.integer("station"), 5);
  EXPECT_EQ(s.text("tcp"), ":0");
  EXPECT_EQ(s.text("writable"), "D0-D9");
  ASSERT_EQ(cell.servers().size(), 1u);
  EXPECT_NE(cell.servers()[0]->describe().find("station 5"), std::string::npos) << cell.servers()[0]->describe();
}

TEST(CellSettings, AnEmptyEndpointTurnsTheYamlsServerOff) {
  Files f;
  const std::string cfg = f.yaml("servers:\n  modbus: {tcp: ':0'}\n");
  CellOverrides o;
  o.servers.push_back(over("modbus", "tcp", {""}, "~modbus_tcp"));
  EXPECT_TRUE(Cell(cfg, o, Cell::Purpose::Check).servers().empty());
  EXPECT_EQ(Cell(cfg, {}, Cell::Purpose::Check).servers().size(), 1u);
}

TEST(CellSettings, ABadOverrideNamesItsOriginAndValue) {
  Files f;
  const std::string cfg = f.yaml("");
  CellOverrides o;
  o.servers.push_back(over("modbus", "id", {"300"}, "--modbus-id"));
  EXPECT_EQ(error_of(cfg, o), "--modbus-id 300: value out of range [1, 247]");
  o.servers = {over("modbus", "gateway_wait", {"150"}, "~modbus_gateway_wait")};
  EXPECT_EQ(error_of(cfg, o), "~modbus_gateway_wait 150: value out of range [0.001, 60] s");
  o.servers = {over("fatek", "idle_timeout", {"forever"}, "--fatek-idle-timeout")};
  EXPECT_NE(error_of(cfg, o).find("--fatek-idle-timeout forever: expected a duration such as 60s or 250ms: bad duration 'forever'"), std::string::npos);
  o.servers = {over("modbus", "tcp", {"a:1", "b:2"}, "--modbus-tcp")};
  EXPECT_EQ(error_of(cfg, o), "--modbus-tcp: given more than once");
  o.servers = {over("modbus", "speed", {"1"}, "--modbus-speed")};
  EXPECT_EQ(error_of(cfg, o), "--modbus-speed: no server setting modbus.speed");
}

TEST(CellSettings, ARepeatableEndpointMakesAServerPerValue) {
  Files f;
  CellOverrides o;
  o.servers.push_back(over("fatek", "tcp", {"127.0.0.1:0", "127.0.0.1:0"}, "--fatek-tcp"));
  EXPECT_EQ(Cell(f.yaml(""), o, Cell::Purpose::Check).servers().size(), 2u);
}

// The gateway could be set from the command line and plc_node but not from the YAML.
TEST(CellSettings, TheGatewayIsSetFromTheYamlToo) {
  Files f;
  const std::string cfg =
      f.yaml("servers:\n  modbus: {tcp: ':0', gateway: /dev/ttyS7, gateway_wait: 250ms, gateway_retries: 4}\n");
  Cell cell(cfg, {}, Cell::Purpose::Check);
  ASSERT_EQ(cell.servers().size(), 1u);
  const std::string d = cell.servers()[0]->describe();
  EXPECT_NE(d.find("wait 250 ms"), std::string::npos) << d;
  EXPECT_NE(d.find("4 retries"), std::string::npos) << d;
  EXPECT_NE(error_of(f.yaml("servers:\n  modbus: {gateway: /dev/ttyS7}\n"), {}).find("needs a Modbus/TCP endpoint too"),
            std::string::npos);
  EXPECT_NE(error_of(f.yaml("servers:\n  modbus: {tcp: ':0', gateway_retries: 11}\n"), {})
                .find("key 'servers.modbus.gateway_retries': value out of range [0, 10]"),
            std::string::npos);
}

TEST(CellSettings, RunSettingsHaveTheYamlsBounds) {
  Files f;
  const std::string cfg = f.yaml("plc: {scan_period: 0.005}\n");
  EXPECT_EQ(Cell(cfg, {}, Cell::Purpose::Check).scan_period_us(), 5000u);
  CellOverrides o;
  o.run.push_back(over("", "scan_period", {"2ms"}, "--scan"));
  EXPECT_EQ(Cell(cfg, o, Cell::Purpose::Check).scan_period_us(), 2000u);
  o.run = {over("", "scan_period", {"50us"}, "--scan")};
  EXPECT_EQ(error_of(cfg, o), "--scan 50us: value out of range [0.0001, 1] s");
  o.run = {over("", "persist_interval", {"61"}, "~persist_interval")};
  EXPECT_EQ(error_of(cfg, o), "~persist_interval 61: value out of range [0.001, 60] s");
  o.run = {over("", "rt_priority", {"100"}, "~rt_priority")};
  EXPECT_EQ(error_of(cfg, o), "~rt_priority 100: value out of range [0, 99]");
}

// plc_cell check reports the servers: section with every other error of the file.
TEST(CellSettings, TheServersSectionsErrorsComeWithTheOthers) {
  Files f;
  const std::string cfg = f.yaml("plc: {scan_period: 5}\nservers:\n  fatek: {station: 0}\n");
  try {
    Cell c(cfg, {}, Cell::Purpose::Check);
    FAIL() << "accepted";
  } catch (const SourceError& e) {
    ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
    EXPECT_NE(e.diagnostics()[0].message.find("plc.scan_period"), std::string::npos);
    EXPECT_NE(e.diagnostics()[1].message.find("servers.fatek.station"), std::string::npos);
    EXPECT_EQ(e.diagnostics()[1].where.line, 4);
  }
}

TEST(Cell, OnlyServingOpensTheStoreAndNothingStartsUntilAsked) {
  Files f;
  const std::string cfg = f.yaml("plc: {retentive: [D0-D9], persist: store.bin}\nservers:\n  modbus: {tcp: '127.0.0.1:0'}\n");
  {
    Cell check(cfg, {}, Cell::Purpose::Check);
    EXPECT_EQ(check.persister(), nullptr);
    EXPECT_FALSE(check.servers().at(0)->status().running);
  }
  EXPECT_FALSE(std::ifstream(f.dir.path() + "/store.bin").good());
  Cell serve(cfg, {}, Cell::Purpose::Serve);
  ASSERT_NE(serve.persister(), nullptr);
  EXPECT_FALSE(serve.servers().at(0)->status().running);
  serve.start_servers();
  EXPECT_TRUE(serve.servers().at(0)->status().running);
  serve.stop();
  EXPECT_FALSE(serve.servers().at(0)->status().running);
  EXPECT_EQ(serve.persister(), nullptr);  // closed: its last image is on disk
  EXPECT_TRUE(std::ifstream(f.dir.path() + "/store.bin").good());
}

// Every setting of every kind can be written the three ways, and says what it is.
TEST(Cell, EveryServerSettingHasItsNamesAndHelp) {
  for (const auto& k : Cell::server_kinds()) {
    std::set<std::string> keys;
    for (const auto& s : k.settings) {
      EXPECT_TRUE(keys.insert(s.key).second) << k.name << "." << s.key;
      EXPECT_FALSE(s.help.empty()) << k.name << "." << s.key;
      EXPECT_EQ(k.option(s).find('_'), std::string::npos) << k.option(s);
      EXPECT_EQ(k.parameter(s).find('-'), std::string::npos) << k.parameter(s);
      if (!s.fallback.empty()) EXPECT_NO_THROW(check_setting(s, s.fallback)) << k.name << "." << s.key;
    }
  }
}
