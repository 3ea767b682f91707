// The TCP loop shared by the protocol servers (io/tcp_listener.h), with a toy protocol of
// newline-terminated lines: loopback, port 0, bounded waits, no sleeps.
#include <future>
#include <mutex>

#include <gtest/gtest.h>

#include "plc_cell/io/tcp_listener.h"
#include "wire.h"

namespace plc_cell {
namespace {

using test::tcp_connect;

// "x\n" -> "ok:x\n"; "bad" closes; "wait" is answered through deliver(); "big" is a
// reply larger than any socket buffer.
class Lines : public TcpProtocol {
 public:
  std::promise<uint64_t> waiting;
  std::promise<Event> event;

  Taken take(uint64_t conn, Session*, std::string& in, std::string& out) override {
    Taken t;
    const size_t nl = in.find('\n');
    if (nl != std::string::npos) {
      const std::string line = in.substr(0, nl);
      in.erase(0, nl + 1);
      t.requests = 1;
      if (line == "bad") t.bad = true;
      else if (line == "wait") {
        t.waiting = true;
        waiting.set_value(conn);
      } else if (line == "big") out.append(size_t(32) << 20, 'b');
      else out += "ok:" + line + "\n";
    }
    t.partial = !in.empty();
    return t;
  }
  void on_event(Event e, int) override {
    std::lock_guard<std::mutex> lk(mu_);
    if (!told_) event.set_value(e);
    told_ = true;
  }

 private:
  std::mutex mu_;
  bool told_ = false;
};

// What the peer sends until it has `want` bytes or closes, within 5 s.
std::string read_some(int fd, size_t want) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  std::string r;
  while (r.size() < want) {
    const auto left =
        std::chrono::duration_cast<std::chrono::milliseconds>(end - std::chrono::steady_clock::now()).count();
    pollfd p{fd, POLLIN, 0};
    if (left <= 0 || poll(&p, 1, int(left)) <= 0) break;
    char buf[256];
    const ssize_t n = recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    r.append(buf, size_t(n));
  }
  return r;
}

bool send_text(int fd, const std::string& s) { return test::write_all(fd, test::Bytes(s.begin(), s.end())); }

TEST(TcpListener, BindsLoopbackOnAFreePortAndAnswersPipelinedRequestsInOrder) {
  Lines p;
  TcpListener l(p, TcpListenerOptions{});
  l.start();
  ASSERT_GT(l.port(), 0);
  EXPECT_EQ(l.options().host, "127.0.0.1");
  const int fd = tcp_connect(l.port());
  ASSERT_GE(fd, 0);
  ASSERT_TRUE(send_text(fd, "a\nb\nc"));  // "c" stays buffered until its newline
  ASSERT_TRUE(send_text(fd, "\n"));
  EXPECT_EQ(read_some(fd, 15), "ok:a\nok:b\nok:c\n");
  close(fd);
  l.stop();
  EXPECT_FALSE(l.running());
}

TEST(TcpListener, ABadFrameClosesOnlyItsConnection) {
  Lines p;
  TcpListener l(p, TcpListenerOptions{});
  l.start();
  const int bad = tcp_connect(l.port()), good = tcp_connect(l.port());
  ASSERT_TRUE(send_text(bad, "bad\n"));
  EXPECT_EQ(read_some(bad, 1), "");  // end of file
  ASSERT_TRUE(send_text(good, "x\n"));
  EXPECT_EQ(read_some(good, 5), "ok:x\n");
  close(bad);
  close(good);
}

TEST(TcpListener, AWaitingRequestIsAnsweredByDeliverBeforeTheNextOne) {
  Lines p;
  TcpListener l(p, TcpListenerOptions{});
  l.start();
  const int fd = tcp_connect(l.port());
  ASSERT_TRUE(send_text(fd, "wait\nafter\n"));
  auto conn = p.waiting.get_future();
  ASSERT_EQ(conn.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  l.deliver(conn.get(), "later\n");
  EXPECT_EQ(read_some(fd, 15), "later\nok:after\n");
  l.deliver(12345, "nobody\n");  // a connection that is not there: dropped
  ASSERT_TRUE(send_text(fd, "y\n"));
  EXPECT_EQ(read_some(fd, 5), "ok:y\n");
  close(fd);
}

TEST(TcpListener, AClientThatDoesNotReadIsDropped) {
  Lines p;
  TcpListenerOptions o;
  o.max_pending_output = 1 << 20;
  TcpListener l(p, o);
  l.start();
  const int fd = tcp_connect(l.port());
  ASSERT_TRUE(send_text(fd, "big\n"));  // and never read
  auto e = p.event.get_future();
  ASSERT_EQ(e.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_EQ(e.get(), TcpProtocol::Event::SlowReader);
  close(fd);
}

TEST(TcpListener, ARequestNotWholeWithinTheFrameTimeoutClosesTheConnection) {
  Lines p;
  TcpListenerOptions o;
  o.limits.frame_timeout_ms = 50;
  TcpListener l(p, o);
  l.start();
  const int fd = tcp_connect(l.port());
  ASSERT_TRUE(send_text(fd, "half"));
  EXPECT_EQ(read_some(fd, 1), "");  // closed by the server
  auto e = p.event.get_future();
  ASSERT_EQ(e.wait_for(std::chrono::seconds(5)), std::future_status::ready);
  EXPECT_EQ(e.get(), TcpProtocol::Event::FrameTimeout);
  close(fd);
}

TEST(TcpListener, ABusyPortIsAnErrorNamingTheEndpoint) {
  Lines p;
  TcpListener a(p, TcpListenerOptions{});
  a.start();
  TcpListenerOptions o;
  o.name = "Toy TCP";
  o.port = a.port();
  TcpListener b(p, o);
  try {
    b.start();
    FAIL() << "bound a busy port";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("Toy TCP 127.0.0.1:" + std::to_string(a.port()) + ": cannot listen"),
              std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace plc_cell
