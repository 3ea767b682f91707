// The cell YAML's servers: section, read against the server kinds' schemas with
// file:line errors, used by `plc_cell run`, each field overridden by its command-line option.
#include <gtest/gtest.h>

#include <fstream>

#include "plc_cell/config/server_kind.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/runtime/cell.h"
#include "run_child.h"
#include "temp_dir.h"

using namespace plc_cell;

namespace {

struct Parsed {
  std::map<std::string, Settings> kinds;
  const Settings& fatek() const { return kinds.at("fatek"); }
  const Settings& modbus() const { return kinds.at("modbus"); }
};

Parsed parse(const std::string& yaml) {
  return {merge_server_settings(Cell::server_kinds(), parse_cell_config(yaml, "cell.yaml", Cell::sections()))};
}

std::string error_of(const std::string& yaml) {
  try {
    parse(yaml);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(ServerSettings, ParsesBothProtocols) {
  const auto s = parse(
      "servers:\n"
      "  fatek: {tcp: ':500', station: 3, writable: [D0-D9, M800], max_connections: 2, idle_timeout: 5s}\n"
      "  modbus: {tcp: '0.0.0.0:502', rtu: /dev/ttyS1, id: 7, writable: none, idle_timeout: 250ms}\n");
  EXPECT_EQ(s.fatek().text("tcp"), ":500");
  EXPECT_EQ(s.fatek().integer("station"), 3);
  EXPECT_EQ(s.fatek().text("writable"), "D0-D9,M800");
  EXPECT_EQ(s.fatek().integer("max_connections"), 2);
  EXPECT_EQ(s.fatek().duration_us("idle_timeout") / 1000, 5000u);
  EXPECT_EQ(s.modbus().text("tcp"), "0.0.0.0:502");
  EXPECT_EQ(s.modbus().text("rtu"), "/dev/ttyS1");
  EXPECT_EQ(s.modbus().integer("id"), 7);
  EXPECT_EQ(s.modbus().text("writable"), "none");
  EXPECT_EQ(s.modbus().integer("max_connections"), 16);
  EXPECT_EQ(s.modbus().duration_us("idle_timeout") / 1000, 250u);
  const auto none = parse("cell: {name: x}\n");
  EXPECT_TRUE(none.fatek().text("tcp").empty() && none.fatek().text("serial").empty() && none.modbus().text("tcp").empty() &&
              none.modbus().text("rtu").empty());
  EXPECT_EQ(none.fatek().text("writable"), "all");
}

TEST(ServerSettings, ErrorsNameTheLineAndKey) {
  EXPECT_EQ(error_of("servers:\n  fatek: {tcp: ':500', statoin: 2}\n"),
            "cell.yaml:2:24: error: key 'servers.fatek.statoin': unknown key (expected one of: idle_timeout, "
            "max_connections, serial, station, tcp, writable)");
  EXPECT_NE(error_of("servers:\n  modbus:\n    writable: D9-D0\n").find("cell.yaml:3:15: error: key 'servers.modbus.writable'"),
            std::string::npos);
  EXPECT_NE(error_of("servers:\n  modbus: {id: 300}\n").find("servers.modbus.id"), std::string::npos);
  EXPECT_NE(error_of("servers:\n  fatek: {idle_timeout: forever}\n").find("servers.fatek.idle_timeout"), std::string::npos);
}

TEST(ServerSettings, PlcCellRunServesWhatTheYamlSaysAndOptionsOverride) {
  TempDir dir;
  std::ofstream(dir.path() + "/p.il") << "ORG M1925\nOUT Y0\nEND\n";
  std::ofstream(dir.path() + "/cell.yaml") << "cell: {program: p.il}\n"
                                              "servers:\n  fatek: {tcp: ':0', writable: [D0-D9]}\n";
  const auto code_of = [](int port, uint32_t reg) {
    fatek::ClientOptions o;
    o.retries = 0;
    fatek::Client c(fatek::tcp_transport("127.0.0.1:" + std::to_string(port)), o);
    try {
      c.write(Address{Area::D, Width::Word, reg}, {1});
    } catch (const fatek::PlcError& e) {
      return char(e.code);
    }
    return '0';
  };
  {
    RunChild child({"--config", dir.path() + "/cell.yaml"});
    EXPECT_NE(child.log.find("serving FATEK TCP 127.0.0.1:"), std::string::npos) << child.log;  // ':0' is loopback
    EXPECT_EQ(code_of(child.ports.at(0), 5), '0');
    EXPECT_EQ(code_of(child.ports.at(0), 20), 'A');
  }
  {
    RunChild child({"--config", dir.path() + "/cell.yaml", "--fatek-writable", "all"});
    EXPECT_EQ(code_of(child.ports.at(0), 20), '0');
  }
}
