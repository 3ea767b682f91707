// `plc_cell run` standing in for a real PLC: the monitor's remote source over FATEK and
// TRi host links to a spawned cell (its port read from its log, waits bounded).
#include <gtest/gtest.h>

#include "../reliability/run_child.h"
#include "plc_cell/remote/fatek_link.h"
#include "plc_cell/remote/tri_link.h"
#include "remote_fixture.h"

namespace plc_cell {
namespace {

using remote_test::error_of;
const std::string& kDir = remote_test::kConveyorDir;

// Reads until the line runs (the demo starts by itself), at most n polls.
monitor::Frame poll_until_running(remote::RemoteSource& s, const std::vector<Address>& addrs, int n = 500) {
  monitor::Frame f;
  for (int i = 0; i < n; ++i) {
    f = s.read(addrs);
    if (f.values[0] == 1) break;
  }
  return f;
}

TEST(PlcCellRunAsAPlc, OverFatek) {
  RunChild cell({"--config", kDir + "conveyor.yaml", "--fatek-tcp", "127.0.0.1:0", "--fatek-writable", "D0-D99"});
  ASSERT_EQ(cell.ports.size(), 1u) << cell.log;
  const auto made = remote_test::conveyor_source<remote::FatekLink>(
      remote_test::on_loopback<remote::FatekLinkOptions>(cell.ports[0]));
  remote::RemoteSource& source = *made;
  const monitor::Frame f = poll_until_running(source, {parse_address("M0"), parse_address("X1")});
  EXPECT_EQ(f.values, (std::vector<uint32_t>{1, 1}));  // line_running; stop_button (NC) simulated
  EXPECT_EQ(f.mode, RunMode::Run);
  source.write(parse_address("D10"), {321});
  EXPECT_EQ(source.read({parse_address("D10")}).values, std::vector<uint32_t>{321});
  EXPECT_NE(error_of([&] { source.write(parse_address("D200"), {1}); }).find("write"), std::string::npos);
  EXPECT_EQ(source.read({parse_address("D200")}).values, std::vector<uint32_t>{0});
  cell.kill9();
  EXPECT_NE(error_of([&] { source.read({parse_address("D10")}); }).find("link down"), std::string::npos);
  EXPECT_FALSE(source.status().servers[0].second.link_up);
}

TEST(PlcCellRunAsAPlc, OverTri) {
  RunChild cell({"--config", kDir + "conveyor.yaml", "--tri-tcp", "127.0.0.1:0"});
  ASSERT_EQ(cell.ports.size(), 1u) << cell.log;
  const auto made = remote_test::conveyor_source<remote::TriLink>(
      remote_test::on_loopback<remote::TriLinkOptions>(cell.ports[0]));
  remote::RemoteSource& source = *made;
  const monitor::Frame f = poll_until_running(source, {parse_address("M0"), parse_address("Y0")});
  EXPECT_EQ(f.values[0], 1u);
  // The TRi reports neither RUN nor STOP: not known until this source switched it.
  EXPECT_FALSE(f.mode_known);
  EXPECT_FALSE(source.status().mode_known);
  source.write(parse_address("D10"), {321});
  EXPECT_EQ(source.read({parse_address("D10")}).values, std::vector<uint32_t>{321});
  // Sixteen outputs are one word of 16: one RVS frame (the TRi's mode is not read).
  std::vector<Address> outputs;
  for (uint32_t i = 0; i < 16; ++i) outputs.push_back(Address{Area::Y, Width::Bit, i});
  const uint64_t before = source.frames();
  const monitor::Frame y = source.read(outputs);
  EXPECT_EQ(source.frames() - before, 1u);
  EXPECT_EQ(y.values.size(), 16u);
  // Not on a TRi: named.
  EXPECT_NE(error_of([&] { source.read({parse_address("D4000")}); }).find("D4000"), std::string::npos);
  EXPECT_NE(error_of([&] { source.force(parse_address("Y0"), ForceAction::Disable); }).find("no DISABLE flag"),
            std::string::npos);
  source.set_mode(RunMode::Stop);  // C2: the ladder halts
  const monitor::Frame stopped = source.read({parse_address("M0")});
  EXPECT_TRUE(stopped.mode_known);
  EXPECT_EQ(stopped.mode, RunMode::Stop);
  source.set_mode(RunMode::Run);
  EXPECT_EQ(source.read({parse_address("M0")}).mode, RunMode::Run);
}

}  // namespace
}  // namespace plc_cell
