// The poll planner: fewest legal frames, and values land back on the right items.
#include <gtest/gtest.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/poll_plan.h"
#include "plc_cell/fatek/server.h"

using namespace plc_cell;
using namespace plc_cell::fatek;

namespace {
std::vector<PollItem> items(std::initializer_list<const char*> texts) {
  std::vector<PollItem> v;
  for (const char* t : texts) v.push_back(parse_register_span(t));
  return v;
}
}  // namespace

TEST(FatekPollPlan, IoImageIsOneMixedFrame) {
  const PollPlan p = plan_poll(items({"WX0:16", "WY0:16"}));
  ASSERT_EQ(p.requests.size(), 1u);
  EXPECT_EQ(p.requests[0].cmd, Cmd::MixedRead);
  EXPECT_EQ(p.requests[0].points.size(), 32u);
  for (const auto& r : p.requests) EXPECT_NO_THROW(encode_request(r));
}

TEST(FatekPollPlan, LongRunsSplitAtTheLegalMaximum) {
  const PollPlan p = plan_poll(items({"R0:200"}));  // 64 + 64 + 64 + 8
  ASSERT_EQ(p.requests.size(), 4u);
  uint32_t total = 0;
  for (const auto& r : p.requests) {
    EXPECT_NO_THROW(encode_request(r));
    total += r.cmd == Cmd::MixedRead ? uint32_t(r.points.size()) : r.count;
  }
  EXPECT_EQ(total, 200u);
  EXPECT_EQ(plan_poll(items({"M0:512"})).requests.size(), 2u);
  EXPECT_EQ(plan_poll(items({"DR0:40"})).requests.size(), 2u);  // 32 + 8 DW
}

TEST(FatekPollPlan, ScatteredPointsShareMixedFrames) {
  // 10 scattered registers of 4 types, weight 12 in all: one cmd 48.
  const PollPlan p = plan_poll(items({"R5", "R100", "R2000", "D7", "D900", "DR50", "Y3", "M100", "RT4", "DD10"}));
  ASSERT_EQ(p.requests.size(), 1u);
  EXPECT_EQ(p.requests[0].cmd, Cmd::MixedRead);
  // Adjacent points with small gaps are read through as one block.
  const PollPlan q = plan_poll(items({"R10", "R12", "R15", "R18:3"}));
  ASSERT_EQ(q.requests.size(), 1u);
  EXPECT_EQ(q.requests[0].cmd, Cmd::ReadRegisters);
  EXPECT_EQ(q.requests[0].count, 11u);
  // Weight over 64 takes a second frame.
  std::vector<PollItem> many;
  for (int i = 0; i < 40; ++i) many.push_back(parse_register_span("DR" + std::to_string(i * 100)));
  EXPECT_EQ(plan_poll(many).requests.size(), 2u);
}

TEST(FatekPollPlan, ValuesComeBackPerItemOverTcp) {
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  TcpServer s(plc, o);
  s.start();
  std::vector<uint32_t> block(100);
  for (uint32_t i = 0; i < 100; ++i) block[i] = 1000 + i;
  plc.write(parse_address("R0"), block);
  plc.write(parse_address("DR200"), {0xCAFEBABE});
  plc.write(parse_address("Y3"), {1});
  plc.write(parse_address("WX16"), {0x8001});
  ClientOptions co;
  co.timeout_ms = 3000;
  Client c(tcp_transport("127.0.0.1:" + std::to_string(s.port())), co);
  const auto its = items({"R0:100", "DR200", "Y3", "Y4", "WX16", "R50:2"});
  const auto v = run_poll(c, its, plan_poll(its));
  ASSERT_EQ(v.size(), its.size());
  EXPECT_EQ(v[0], block);
  EXPECT_EQ(v[1], (std::vector<uint32_t>{0xCAFEBABE}));
  EXPECT_EQ(v[2], (std::vector<uint32_t>{1}));
  EXPECT_EQ(v[3], (std::vector<uint32_t>{0}));
  EXPECT_EQ(v[4], (std::vector<uint32_t>{0x8001}));
  EXPECT_EQ(v[5], (std::vector<uint32_t>{1050, 1051}));
}
