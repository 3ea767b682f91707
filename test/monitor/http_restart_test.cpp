// The monitor's server stopped and started again, as a cell stops and starts its servers:
// the stop closes every connection, the start serves again on the same address with the
// same session token, pages and API alike.
#include "monitor_fixture.h"

namespace plc_cell {
namespace monitor_test {
namespace {

TEST_F(MonitorTest, AStoppedServerStartsAgainOnItsAddress) {
  serve();
  const std::string t = token();
  ASSERT_EQ(t.size(), 32u);
  WsClient page(port);
  page.send(R"({"subscribe":{"watch":["Y0"],"rate_hz":50}})");
  ASSERT_FALSE(page.next("frame").is_null());

  server->stop();
  EXPECT_FALSE(server->status().running);
  EXPECT_TRUE(page.closed_within(std::chrono::milliseconds(3000)));  // its connections go with it
  EXPECT_EQ(http_get(port, "/api/status").status, 0);                 // and nothing answers

  server->start();
  EXPECT_TRUE(server->status().running);
  EXPECT_EQ(server->port(), port);  // the port the first start picked
  EXPECT_EQ(token(), t);
  plc.set_input(0, true);
  scan();
  EXPECT_EQ(http_get(port, "/api/read?a=Y0").json()["values"]["Y0"], 1);
  WsClient again(port);
  again.send(R"({"subscribe":{"watch":["Y0"],"rate_hz":50}})");
  const auto f = again.next("frame");
  ASSERT_FALSE(f.is_null());
  EXPECT_EQ(f["values"]["Y0"], 1);
  // A second stop and start: the same again.
  server->stop();
  server->start();
  EXPECT_EQ(http_get(port, "/api/status").status, 200);
}

}  // namespace
}  // namespace monitor_test
}  // namespace plc_cell
