// The monitor's connections under clients that hold them without finishing a request: the
// headers' deadline, and the slot a full table gives to a new client (docs/monitor-api.md,
// "Errors and limits").
#include "monitor_fixture.h"

namespace plc_cell {
namespace monitor_test {
namespace {

constexpr const char* kHalfRequest = "GET /api/session HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Half: ";

// Polls cond every 10 ms until it holds or bound passes; false past the bound.
template <typename F>
bool within(std::chrono::milliseconds bound, F cond) {
  const auto end = std::chrono::steady_clock::now() + bound;
  while (!cond()) {
    if (std::chrono::steady_clock::now() >= end) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));  // polling, not waiting for a result
  }
  return true;
}

TEST_F(MonitorTest, SixtyHalfRequestsDoNotLockAFreshPageOut) {
  serve();  // the defaults: 16 connections, headers within 2 s, idle connections closed after 60 s
  Stallers held(port, 60, kHalfRequest);
  // The fresh page is answered at once: it takes the slot of the connection that has gone
  // longest without completing a request (http_get gives up after 5 s).
  const auto page = http_get(port, "/");
  EXPECT_EQ(page.status, 200) << page.body;
  const auto session = http_get(port, "/api/session");
  EXPECT_EQ(session.status, 200) << session.body;
  EXPECT_LE(server->status().connections, 16u);
}

TEST_F(MonitorTest, HalfARequestIsClosedAtTheHeadersDeadline) {
  settings.header_timeout_us = 300'000;
  serve();
  // Far within the idle timeout (60 s), but past the headers' deadline.
  EXPECT_TRUE(closed_after_sending(port, kHalfRequest, std::chrono::milliseconds(5000)));
  Stallers held(port, 5, kHalfRequest);
  EXPECT_TRUE(within(std::chrono::seconds(5), [&] { return held.open() == 0; }))
      << held.open() << " of 5 half requests still open";
  // A whole request on a kept-alive connection is not cut by it.
  EXPECT_EQ(http_get(port, "/api/session").status, 200);
}

TEST_F(MonitorTest, ASubscribedPageKeepsItsSlotAgainstHalfRequests) {
  settings.max_connections = 4;
  serve();
  WsClient page(port);
  page.send(R"({"subscribe":{"watch":["R0"],"rate_hz":20}})");
  ASSERT_FALSE(page.next("frame").is_null());
  Stallers held(port, 20, kHalfRequest);
  EXPECT_EQ(http_get(port, "/api/session").status, 200);
  // The page still gets its frames: the half requests took each other's slots, not its.
  for (int i = 0; i < 5; ++i) ASSERT_FALSE(page.next("frame").is_null()) << i;
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
