// tri_bridge against a TRi that answers late but in order, and one that garbles every poll
// while its IR answers: no late reply is ever taken for a later request's answer (a host-link
// reply repeats no address), and a link that delivers no good poll is not reported OK.
// Waits are bounded waits on what the bridge reports; the device's lateness is its own.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <map>
#include <thread>

#include "../bridge_collector.h"
#include "../fatek/fatek_link.h"
#include "../reliability/pty_proxy.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/tri/bridge.h"
#include "plc_cell/tri/frame.h"
#include "plc_cell/tri/server.h"
#include "plc_cell/tri/slave.h"

using namespace plc_cell;
using namespace plc_cell::tri;
using Clock = std::chrono::steady_clock;

namespace {

class Collector : public bridge_test::Collector {
 public:
  Bridge::Sinks sinks() { return bridge_test::Collector::sinks<Bridge::Sinks>(); }
};

// A TRi on loopback TCP: the soft PLC's slave answers each request, delay_ms after it came
// and in order; with garble, every reply but IR's gets a wrong FCS.
class FakeTri {
 public:
  FakeTri(Plc& plc, int delay_ms, bool garble) : slave_(plc, 1), delay_ms_(delay_ms), garble_(garble) {
    listen_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof sa;
    if (::bind(listen_, reinterpret_cast<sockaddr*>(&sa), len) != 0 || ::listen(listen_, 4) != 0 ||
        ::getsockname(listen_, reinterpret_cast<sockaddr*>(&sa), &len) != 0)
      throw std::runtime_error("listen");
    port_ = ntohs(sa.sin_port);
    thread_ = std::thread([this] { run(); });
  }
  ~FakeTri() {
    stop_ = true;
    thread_.join();
    for (auto& c : clients_) ::close(c.first);
    ::close(listen_);
  }
  int port() const { return port_; }
  int requests() const { return requests_; }

 private:
  struct Reply {
    Clock::time_point due;
    int fd;
    std::string bytes;
  };
  void run() {
    while (!stop_) {
      std::vector<pollfd> p{{listen_, POLLIN, 0}};
      for (auto& c : clients_) p.push_back({c.first, POLLIN, 0});
      int wait = 20;
      if (!queue_.empty())
        wait = int(std::max<int64_t>(0, std::chrono::duration_cast<std::chrono::milliseconds>(queue_.front().due - Clock::now()).count()));
      ::poll(p.data(), p.size(), std::min(wait, 20));
      if (p[0].revents & POLLIN) {
        const int fd = ::accept4(listen_, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd >= 0) clients_[fd];
      }
      for (size_t i = 1; i < p.size(); ++i) {
        if (!(p[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
        char buf[512];
        const ssize_t n = ::read(p[i].fd, buf, sizeof buf);
        if (n <= 0) {  // gone: its replies with it
          ::close(p[i].fd);
          clients_.erase(p[i].fd);
          for (auto it = queue_.begin(); it != queue_.end();) it = it->fd == p[i].fd ? queue_.erase(it) : it + 1;
          continue;
        }
        std::string& in = clients_[p[i].fd];
        in.append(buf, size_t(n));
        for (size_t cr; (cr = in.find('\r')) != std::string::npos; in.erase(0, cr + 1)) {
          const std::string req = in.substr(0, cr + 1);
          std::string reply = slave_.answer(req);
          ++requests_;
          if (garble_ && req.find("IR") == std::string::npos && reply.size() > 3) reply[reply.size() - 3] ^= 1;  // the last FCS digit
          queue_.push_back({Clock::now() + std::chrono::milliseconds(delay_ms_), p[i].fd, reply});
        }
      }
      while (!queue_.empty() && queue_.front().due <= Clock::now()) {
        (void)!::send(queue_.front().fd, queue_.front().bytes.data(), queue_.front().bytes.size(), MSG_NOSIGNAL);
        queue_.pop_front();
      }
    }
  }
  Slave slave_;
  int delay_ms_;
  bool garble_;
  int listen_ = -1, port_ = 0;
  std::atomic<bool> stop_{false};
  std::atomic<int> requests_{0};
  std::map<int, std::string> clients_;
  std::deque<Reply> queue_;
  std::thread thread_;
};

BridgeConfig three_dms() {
  return parse_bridge_config(YAML::Load("groups: [{name: recipe, rate: 20, points: [\"DM[1]:3\"]}]"), "tri.yaml");
}

// Every group the bridge delivered holds the device's values, and none is DM[n-1]'s.
void expect_only_true_values(Collector& c) {
  for (const auto& g : c.groups)
    if (g.ok) EXPECT_EQ(g.values, (std::vector<uint32_t>{111, 222, 333}));
}

}  // namespace

// The setup scaled down: replies 60 ms late, ~timeout 50 ms, ~retries 1.
TEST(TriSlowDevice, ALateReplyIsNeverTakenForTheNextRequestOverTcp) {
  Plc plc;
  plc.write(parse_address("D0"), {111, 222, 333});
  FakeTri dev(plc, 60, false);
  BridgeConfig cfg = bridge_test::loopback_link(dev.port(), three_dms());
  cfg.timeout_s = 0.05;
  cfg.retries = 1;
  Collector c;
  Bridge b(cfg, c.sinks());
  b.start();
  // Every request is late: many requests and failures, and never a published value.
  ASSERT_TRUE(c.wait([&] { return dev.requests() >= 30 && c.errors.size() >= 10; }, 30));
  b.stop();
  expect_only_true_values(c);
  for (const auto& g : c.groups) EXPECT_FALSE(g.ok);
  EXPECT_GE(b.status().errors, 10u);
}

// The same over a serial line: the slow device is the soft PLC's serial server behind a
// proxy that delays each reply (300 ms; timeout 200 ms); a line cannot be reconnected, it is
// drained until quiet for the timeout, so the replies come between the timeout and twice it,
// 100 ms from either, for a loaded machine's late threads.
TEST(TriSlowDevice, ALateReplyIsNeverTakenForTheNextRequestOverASerialLine) {
  LateDeviceLine proxy(300);
  Plc plc;
  plc.write(parse_address("D0"), {111, 222, 333});
  SerialServer server(plc, parse_serial_settings(proxy.device_link() + ":38400:8N1", "8N1"), ServerOptions{});
  server.start();
  BridgeConfig cfg = three_dms();
  cfg.serial = proxy.client_link();
  cfg.timeout_s = 0.2;
  cfg.retries = 1;
  cfg.io_rate_hz = 20;
  cfg.backoff_min_s = 0.01;
  cfg.backoff_max_s = 0.05;
  Collector c;
  Bridge b(cfg, c.sinks());
  b.start();
  ASSERT_TRUE(c.wait([&] { return c.errors.size() >= 4; }, 30));
  expect_only_true_values(c);
  for (const auto& g : c.groups) EXPECT_FALSE(g.ok);
  // In time again: the same link delivers the true values.
  proxy.set_delay_ms(0);
  c.clear();
  ASSERT_TRUE(c.wait([&] { return !c.groups.empty() && c.groups.back().ok; }, 30)) << b.status().last_error;
  b.stop();
  server.stop();
  expect_only_true_values(c);
}

// Every poll garbled while IR answers: the link reconnects again and again, and is not OK.
TEST(TriSlowDevice, ALinkThatDeliversNoGoodPollIsNotOk) {
  Plc plc;
  plc.write(parse_address("D0"), {111, 222, 333});
  FakeTri dev(plc, 0, true);
  BridgeConfig cfg = bridge_test::loopback_link(dev.port(), three_dms());
  Collector c;
  Bridge b(cfg, c.sinks());
  EXPECT_EQ(link_health(b.status()).level, LinkLevel::Error);  // not connected yet
  b.start();
  ASSERT_TRUE(c.wait([&] { return b.status().reconnects >= 5 && b.status().failed_polls_in_row >= kLinkErrorPolls; }, 30));
  // Whenever it is asked over the next ten failures, connected or between two
  // reconnections: ERROR.
  const size_t n0 = c.errors.size();
  int asked = 0;
  ASSERT_TRUE(c.wait([&] {
    const LinkStatus s = b.status();
    const LinkHealth h = link_health(s);
    ++asked;
    EXPECT_EQ(h.level, LinkLevel::Error) << h.message;
    if (s.connected) {
      EXPECT_NE(h.message.find("polls failed: "), std::string::npos) << h.message;
    }
    return c.errors.size() >= n0 + 10;
  }, 30));
  EXPECT_GE(asked, 10);
  EXPECT_FALSE(b.status().delivered);
  b.stop();
  for (const auto& g : c.groups) EXPECT_FALSE(g.ok);
}

// The levels, as docs/tri.md states them.
TEST(TriSlowDevice, LinkHealthLevels) {
  LinkStatus s;
  s.last_error = "x";
  EXPECT_EQ(link_health(s).level, LinkLevel::Error);
  s.connected = true;
  EXPECT_EQ(link_health(s).level, LinkLevel::Ok);
  EXPECT_EQ(link_health(s).message, "connected");
  s.failed_polls_in_row = 1;
  EXPECT_EQ(link_health(s).level, LinkLevel::Warn);
  s.failed_polls_in_row = 2;
  EXPECT_EQ(link_health(s).level, LinkLevel::Warn);
  s.failed_polls_in_row = 3;
  EXPECT_EQ(link_health(s).level, LinkLevel::Error);
  EXPECT_EQ(link_health(s).message, "connected, but the last 3 polls failed: x");
}
