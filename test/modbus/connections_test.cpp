// The time bounds shared by the TCP servers (io/connections.h), on a virtual clock:
// time points are made by the test, nothing waits.
#include <gtest/gtest.h>

#include "plc_cell/io/connections.h"

namespace plc_cell {
namespace {

using C = Connections<int>;
using ms = std::chrono::milliseconds;

TEST(Connections, APartialFrameExpiresFromItsFirstByteNotItsLast) {
  C t(ConnectionLimits{4, 60000, 1000});
  const auto t0 = C::Clock::time_point{} + ms(5000);
  int ev;
  ASSERT_EQ(t.admit(10, t0, &ev), C::Admit::Accepted);
  auto& c = t.all()[0];
  // Bytes keep trickling in; the deadline stays where the first one put it.
  C::partial(c, t0 + ms(100));
  C::partial(c, t0 + ms(999));
  EXPECT_EQ(t.expired(c, t0 + ms(1099)), C::Expiry::None);
  EXPECT_EQ(t.expired(c, t0 + ms(1100)), C::Expiry::Frame);
  EXPECT_EQ(t.poll_timeout_ms(t0 + ms(600)), 501);
}

TEST(Connections, IdleCountsFromTheLastCompleteRequest) {
  C t(ConnectionLimits{4, 3000, 1000});
  const auto t0 = C::Clock::time_point{} + ms(5000);
  int ev;
  t.admit(10, t0, &ev);
  auto& c = t.all()[0];
  C::complete(c, t0 + ms(2000));
  EXPECT_EQ(t.expired(c, t0 + ms(4999)), C::Expiry::None);
  EXPECT_EQ(t.expired(c, t0 + ms(5000)), C::Expiry::Idle);
}

TEST(Connections, AFullTableGivesTheStalestSlotToANewClient) {
  C t(ConnectionLimits{2, 60000, 1000});
  const auto t0 = C::Clock::time_point{} + ms(5000);
  int ev;
  t.admit(10, t0, &ev);
  t.admit(11, t0 + ms(10), &ev);
  // Both recent: the new client is refused.
  EXPECT_EQ(t.admit(12, t0 + ms(500), &ev), C::Admit::Refused);
  EXPECT_EQ(t.size(), 2u);
  // fd 11 keeps completing requests; fd 10 has completed none for over the frame timeout.
  C::complete(t.all()[1], t0 + ms(1400));
  ASSERT_EQ(t.admit(12, t0 + ms(1500), &ev), C::Admit::Evicted);
  EXPECT_EQ(ev, 10);
  EXPECT_EQ(t.size(), 2u);
  EXPECT_EQ(t.all()[0].fd, 11);
  EXPECT_EQ(t.all()[1].fd, 12);
  // A connection with work out (a forwarded request) is never evicted.
  t.all()[0].waiting = true;
  EXPECT_EQ(t.admit(13, t0 + ms(2000), &ev), C::Admit::Refused);
  EXPECT_EQ(t.admit(13, t0 + ms(2600), &ev), C::Admit::Evicted);
  EXPECT_EQ(ev, 12);
}

}  // namespace
}  // namespace plc_cell
