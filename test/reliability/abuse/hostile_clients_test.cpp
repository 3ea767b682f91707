// Hostile clients against `plc_cell run` as a child process on 127.0.0.1: random bytes,
// partial and oversized frames, slowloris, more connections than the cap, half-open
// connections, clients that never read, and a flood. For each: the process stays up,
// a well-behaved client has every request answered, in order, fds and RSS end where
// they began, CPU stays flat while hostile peers sit idle, a refused request changes
// nothing, and the scan has no watchdog fault. Nothing here asserts on latency (a loaded
// machine stretches it); `make soak` reports the well-behaved clients' latency under
// abuse. Bounded in count and time; results are waited for by polling with deadlines,
// never by sleeping.
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "../../modbus/wire.h"
#include "../run_child.h"
#include "../temp_dir.h"
#include "plc_cell/core/address.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/frame.h"
#include "proc_stats.h"

namespace {

using plc_cell::test::Bytes;
using Clock = std::chrono::steady_clock;

int port_of(const std::string& log, const std::string& what) {
  const auto k = log.find("serving " + what + " 127.0.0.1:");
  if (k == std::string::npos) return -1;
  return std::stoi(log.substr(k + 8 + what.size() + 11));
}

// Polls cond every 10 ms until it holds or deadline_ms passes.
bool eventually(const std::function<bool()>& cond, int deadline_ms) {
  const auto end = Clock::now() + std::chrono::milliseconds(deadline_ms);
  while (!cond()) {
    if (Clock::now() >= end) return false;
    ::poll(nullptr, 0, 10);
  }
  return true;
}

// True once the peer has closed or reset the connection, seen without reading what it
// sent: an end of file (POLLRDHUP) or a reset (POLLERR/POLLHUP).
bool dropped_by_peer(int fd) {
  pollfd p{fd, POLLRDHUP, 0};
  return ::poll(&p, 1, 0) > 0 && (p.revents & (POLLRDHUP | POLLHUP | POLLERR));
}

void report(const std::string& name, const std::string& figures) {
  std::printf("[ figures  ] %s: %s\n", name.c_str(), figures.c_str());
  ::testing::Test::RecordProperty(name, figures);
}

class HostileClients : public ::testing::Test {
 protected:
  void SetUp() override {
    std::ofstream(dir_.path() + "/p.il") << "ORG X1\nOUT Y0\nEND\n";
    child_ = std::make_unique<RunChild>(
        std::vector<std::string>{"--program", dir_.path() + "/p.il", "--scan", "10ms", "--modbus-tcp", "127.0.0.1:0",
                                 "--fatek-tcp", "127.0.0.1:0"},
        2);
    mb_ = port_of(child_->log, "Modbus TCP");
    ft_ = port_of(child_->log, "FATEK TCP");
    ASSERT_GT(mb_, 0) << child_->log;
    ASSERT_GT(ft_, 0) << child_->log;
    // Warm up (first allocations, thread stacks) before the baseline.
    ASSERT_EQ(modbus_served(50), 50);
    ASSERT_EQ(fatek_served(20), 20);
    fds0_ = abuse::fd_count(pid());
    rss0_ = abuse::rss_kb(pid());
    mem0_ = holding(0, 100);
  }
  void TearDown() override {
    if (!child_ || child_->pid() < 0) return;
    const std::string log = child_->terminate();
    EXPECT_EQ(log.find("fault:"), std::string::npos) << log;
    EXPECT_NE(log.find(" scans, cycle avg"), std::string::npos) << log;
  }
  pid_t pid() const { return child_->pid(); }

  // Well-behaved Modbus client: n reads of 10 registers on one connection. Counts the
  // replies that came in order: each carries its request's transaction id and 10 values.
  int modbus_served(int n) {
    int served = 0;
    const int fd = plc_cell::test::tcp_connect(mb_);
    if (fd < 0) return 0;
    for (int i = 0; i < n; ++i) {
      const uint16_t tid = uint16_t(0x100 + i);
      if (!plc_cell::test::write_all(fd, plc_cell::test::mbap(tid, 1, {3, 0, 0, 0, 10}))) break;
      const Bytes r = plc_cell::test::read_tcp_reply(fd, 2000);
      if (r.size() != 9 + 20 || (r[0] << 8 | r[1]) != tid || r[7] != 3 || r[8] != 20) break;
      ++served;
    }
    ::close(fd);
    return served;
  }
  // Well-behaved FATEK client: n reads of R0..R9, each answered with 10 values.
  int fatek_served(int n) {
    int served = 0;
    try {
      plc_cell::fatek::ClientOptions o;
      o.retries = 0;
      plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport("127.0.0.1:" + std::to_string(ft_)), o);
      for (int i = 0; i < n; ++i) {
        if (c.read(plc_cell::Address{plc_cell::Area::R, plc_cell::Width::Word, 0}, 10).size() != 10) break;
        ++served;
      }
    } catch (const std::exception&) {
    }
    return served;
  }
  std::vector<uint16_t> holding(uint16_t a, uint16_t n) {
    std::vector<uint16_t> v;
    const int fd = plc_cell::test::tcp_connect(mb_);
    if (fd < 0) return v;
    plc_cell::test::write_all(fd, plc_cell::test::mbap(7, 1, {3, uint8_t(a >> 8), uint8_t(a), uint8_t(n >> 8), uint8_t(n)}));
    const Bytes r = plc_cell::test::read_tcp_reply(fd, 2000);
    for (size_t i = 9; i + 1 < r.size(); i += 2) v.push_back(uint16_t(r[i] << 8 | r[i + 1]));
    ::close(fd);
    return v;
  }
  // After the abuse: back to the baseline (the server closed what the peers left).
  void expect_flat(const std::string& name, int deadline_ms = 5000) {
    EXPECT_TRUE(eventually([&] { return abuse::fd_count(pid()) <= fds0_; }, deadline_ms))
        << name << ": fds " << abuse::fd_count(pid()) << " vs " << fds0_;
    const int fds = abuse::fd_count(pid());
    const long rss = abuse::rss_kb(pid());
    EXPECT_LT(rss, rss0_ + 4096) << name << ": RSS " << rss << " kB vs " << rss0_ << " kB";
    EXPECT_EQ(holding(0, 100), mem0_) << name << ": memory changed";
    report(name + ".fds_rss", "fds " + std::to_string(fds0_) + " -> " + std::to_string(fds) +
                                  ", RSS " + std::to_string(rss0_) + " -> " + std::to_string(rss) + " kB");
  }
  // Every request of a well-behaved client answered, in order.
  void expect_served(const std::string& name) {
    EXPECT_EQ(modbus_served(200), 200) << name;
    EXPECT_EQ(fatek_served(100), 100) << name;
  }

  TempDir dir_;
  std::unique_ptr<RunChild> child_;
  int mb_ = -1, ft_ = -1, fds0_ = 0;
  long rss0_ = 0;
  std::vector<uint16_t> mem0_;
};

TEST_F(HostileClients, RandomBytesAndPartialFrames) {
  std::mt19937 rng(42);
  for (int port : {mb_, ft_}) {
    for (int i = 0; i < 200; ++i) {
      const int fd = plc_cell::test::tcp_connect(port);
      if (fd < 0) continue;
      Bytes junk(1 + rng() % (i % 2 ? 5 : 300));
      for (auto& b : junk) b = uint8_t(rng());
      if (port == ft_ && i % 3 == 0) junk[0] = 0x02;  // FATEK: a frame begun and never ended
      plc_cell::test::write_all(fd, junk);
      ::close(fd);
    }
  }
  // Partial frames left open: the frame timeout closes them; meanwhile no CPU is burnt.
  std::vector<int> open_fds;
  for (int i = 0; i < 12; ++i) {
    const int fd = plc_cell::test::tcp_connect(i % 2 ? mb_ : ft_);
    plc_cell::test::write_all(fd, i % 2 ? Bytes{0, 1, 0, 0, 0} : Bytes{0x02, '0', '1'});
    open_fds.push_back(fd);
  }
  const uint64_t cpu0 = abuse::cpu_ticks(pid());
  const auto t0 = Clock::now();
  // Each stalled peer is closed by the server (we see end of file) within the frame timeout.
  for (int fd : open_fds) {
    EXPECT_TRUE(eventually([&] {
      char c;
      pollfd p{fd, POLLIN, 0};
      return ::poll(&p, 1, 0) > 0 && ::recv(fd, &c, 1, MSG_DONTWAIT) <= 0;
    }, 3000));
    ::close(fd);
  }
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  const double cpu = abuse::ticks_to_s(abuse::cpu_ticks(pid()) - cpu0);
  char b[96];
  std::snprintf(b, sizeof b, "CPU %.2f s over %.2f s with 12 stalled partial frames", cpu, secs);
  report("RandomBytesAndPartialFrames.cpu", b);
  EXPECT_LT(cpu, 0.5 * secs + 0.1);  // a spinning server thread would be ~1.0 x secs
  expect_served("RandomBytesAndPartialFrames");
  expect_flat("RandomBytesAndPartialFrames");
}

TEST_F(HostileClients, OversizedFramesAndBadHeaders) {
  // MBAP length 2000, protocol id 7, and a FATEK frame longer than its maximum.
  for (int i = 0; i < 50; ++i) {
    int fd = plc_cell::test::tcp_connect(mb_);
    Bytes big = {0, 1, 0, 0, 0x07, 0xD0, 1, 3};
    big.resize(2100, 0x41);
    plc_cell::test::write_all(fd, big);
    EXPECT_TRUE(plc_cell::test::read_tcp_reply(fd, 2000).empty());  // closed, no answer
    ::close(fd);
    fd = plc_cell::test::tcp_connect(ft_);
    Bytes fb(1200, '0');
    fb[0] = 0x02;
    fb.back() = 0x03;
    plc_cell::test::write_all(fd, fb);
    ::close(fd);
  }
  expect_served("OversizedFramesAndBadHeaders");
  expect_flat("OversizedFramesAndBadHeaders");
}

TEST_F(HostileClients, SlowlorisDoesNotHoldTheSlots) {
  // More trickling clients than slots, one byte every 200 ms of a valid request: none
  // completes within the frame timeout (1 s).
  std::vector<int> slow;
  for (int i = 0; i < 20; ++i) slow.push_back(plc_cell::test::tcp_connect(mb_));
  for (int i = 0; i < 10; ++i) slow.push_back(plc_cell::test::tcp_connect(ft_));
  const Bytes mreq = plc_cell::test::mbap(1, 1, {3, 0, 0, 0, 1});
  const std::string freq = "\x02" "0146" "01R00000";
  std::atomic<bool> stop{false};
  std::thread trickle([&] {
    for (size_t k = 0; k < 40 && !stop; ++k) {
      for (size_t i = 0; i < slow.size(); ++i) {
        const uint8_t b = i < 20 ? mreq[k % mreq.size()] : uint8_t(freq[k % freq.size()]);
        (void)!::send(slow[i], &b, 1, MSG_NOSIGNAL | MSG_DONTWAIT);
      }
      ::poll(nullptr, 0, 200);  // the attack's pace, not a wait for a result
    }
  });
  // A new client gets a slot and is served within a bounded time, repeatedly.
  int served = 0;
  const auto t0 = Clock::now();
  for (int round = 0; round < 5; ++round) {
    EXPECT_TRUE(eventually([&] { return modbus_served(5) == 5 && fatek_served(5) == 5; }, 3000)) << "round " << round;
    ++served;
  }
  stop = true;
  trickle.join();
  for (int fd : slow) ::close(fd);
  char b[96];
  std::snprintf(b, sizeof b, "%d of 5 rounds served under 30 trickling clients in %.2f s", served,
                std::chrono::duration<double>(Clock::now() - t0).count());
  report("SlowlorisDoesNotHoldTheSlots", b);
  expect_served("SlowlorisDoesNotHoldTheSlots");
  expect_flat("SlowlorisDoesNotHoldTheSlots");
}

TEST_F(HostileClients, MoreConnectionsThanTheCapAndHalfOpen) {
  std::vector<int> many;
  for (int i = 0; i < 40; ++i) many.push_back(plc_cell::test::tcp_connect(mb_));
  for (int i = 0; i < 20; ++i) many.push_back(plc_cell::test::tcp_connect(ft_));
  // Half-open: we shut our sending side; the server sees end of file and closes.
  for (size_t i = 0; i < many.size(); i += 2) ::shutdown(many[i], SHUT_WR);
  // A newcomer may be refused while every slot is younger than the frame timeout (1 s):
  // evicting a peer that has had no time to send its first request would let a burst of
  // connects shut out every client. Past that, a slot is freed by a closing half-open peer
  // or taken from the longest-silent one, so a new client is served within the timeout plus
  // a margin, however the server's accepts interleaved with the burst.
  const auto t0 = Clock::now();
  EXPECT_TRUE(eventually([&] { return modbus_served(1) == 1 && fatek_served(1) == 1; }, 3000));
  report("MoreConnectionsThanTheCapAndHalfOpen.admitted",
         "a new client served after " +
             std::to_string(std::chrono::duration_cast<std::chrono::milliseconds>(Clock::now() - t0).count()) +
             " ms with 60 peers connected");
  expect_served("MoreConnectionsThanTheCapAndHalfOpen");
  for (int fd : many) ::close(fd);
  expect_flat("MoreConnectionsThanTheCapAndHalfOpen");
}

TEST_F(HostileClients, ClientsThatNeverReadTheirReplies) {
  // Pipeline thousands of 125-register reads and never read: the socket buffers fill
  // and the server drops those clients instead of waiting on them. The drop is seen on
  // each socket as the server's end of file or reset, with the replies still unread.
  std::vector<int> hogs;
  Bytes burst;
  for (int i = 0; i < 400; ++i) {
    const Bytes r = plc_cell::test::mbap(uint16_t(i), 1, {3, 0, 0, 0, 125});
    burst.insert(burst.end(), r.begin(), r.end());
  }
  const int small = 4096;
  for (int i = 0; i < 4; ++i) {
    const int fd = plc_cell::test::tcp_connect(mb_);
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    hogs.push_back(fd);
  }
  // FATEK: requests never read until its output limit (64 KiB pending).
  const int f = plc_cell::test::tcp_connect(ft_);
  setsockopt(f, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
  std::string many;
  for (int i = 0; i < 2000; ++i) many += plc_cell::fatek::encode_frame(plc_cell::fatek::Frame{1, 0x46, "40R00000"});
  std::vector<int> all = hogs;
  all.push_back(f);
  // Keep the requests coming to each client not yet dropped, until every one is (bounded by
  // the deadline, not by a count of bursts: on a loaded machine the server reads slowly,
  // most of a burst is refused by the full socket, and the replies that fill the server's
  // side take longer to pile up).
  int rounds = 0;
  const auto all_dropped = [&] {
    return std::all_of(all.begin(), all.end(), [](int fd) { return dropped_by_peer(fd); });
  };
  EXPECT_TRUE(eventually([&] {
    if (all_dropped()) return true;
    ++rounds;
    for (int fd : hogs)
      if (!dropped_by_peer(fd)) (void)!::send(fd, burst.data(), burst.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    if (!dropped_by_peer(f)) (void)!::send(f, many.data(), many.size(), MSG_NOSIGNAL | MSG_DONTWAIT);
    return false;
  }, 30000)) << "Modbus clients dropped: " << dropped_by_peer(hogs[0]) << dropped_by_peer(hogs[1])
             << dropped_by_peer(hogs[2]) << dropped_by_peer(hogs[3]) << ", FATEK client dropped: " << dropped_by_peer(f);
  report("ClientsThatNeverReadTheirReplies", "4 Modbus and 1 FATEK client dropped after " + std::to_string(rounds) +
                                                 " bursts of requests");
  expect_served("ClientsThatNeverReadTheirReplies");
  for (int fd : all) ::close(fd);
  expect_flat("ClientsThatNeverReadTheirReplies");
}

TEST_F(HostileClients, FloodOfValidRequestsFrom16Clients) {
  std::atomic<bool> stop{false};
  std::atomic<uint64_t> answered{0};
  std::vector<std::thread> flood;
  for (int i = 0; i < 16; ++i)
    flood.emplace_back([&, i] {
      const bool fatek = i >= 12;  // 12 Modbus, 4 FATEK: both servers keep a free slot
      if (fatek) {
        try {
          plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport("127.0.0.1:" + std::to_string(ft_)));
          for (int k = 0; k < 20000 && !stop; ++k) {
            c.read(plc_cell::Address{plc_cell::Area::R, plc_cell::Width::Word, 0}, 64);
            ++answered;
          }
        } catch (const std::exception&) {
        }
        return;
      }
      const int fd = plc_cell::test::tcp_connect(mb_);
      for (int k = 0; k < 20000 && !stop; ++k) {
        if (!plc_cell::test::write_all(fd, plc_cell::test::mbap(uint16_t(k), 1, {3, 0, 0, 0, 125}))) break;
        if (plc_cell::test::read_tcp_reply(fd, 2000).empty()) break;
        ++answered;
      }
      ::close(fd);
    });
  const int m = modbus_served(300);
  const int fl = fatek_served(150);
  stop = true;
  for (auto& t : flood) t.join();
  EXPECT_EQ(m, 300);
  EXPECT_EQ(fl, 150);
  EXPECT_GT(answered.load(), 0u);
  report("FloodOfValidRequestsFrom16Clients",
         std::to_string(answered.load()) + " flood requests answered beside 300 Modbus and 150 FATEK reads");
  expect_flat("FloodOfValidRequestsFrom16Clients");
}

TEST_F(HostileClients, MalformedRequestsChangeNothing) {
  const int fd = plc_cell::test::tcp_connect(mb_);
  std::mt19937 rng(7);
  int exceptions = 0;
  for (int i = 0; i < 2000; ++i) {
    Bytes pdu(1 + rng() % 20);
    for (auto& b : pdu) b = uint8_t(rng());
    // Odd: the writes, aimed at unmapped R4168 or malformed; even: unknown codes.
    pdu[0] = i % 2 ? uint8_t(std::vector<int>{5, 6, 15, 16, 23}[(i / 2) % 5]) : uint8_t(0x40 | (rng() & 0x3F));
    if (pdu[0] == 5 || pdu[0] == 6 || pdu[0] == 15 || pdu[0] == 16 || pdu[0] == 23) {
      if (pdu.size() >= 3) pdu[1] = 0x10, pdu[2] = 0x48;  // aimed at unmapped R4168, or malformed
    }
    ASSERT_TRUE(plc_cell::test::write_all(fd, plc_cell::test::mbap(uint16_t(i), 1, pdu)));
    const Bytes r = plc_cell::test::read_tcp_reply(fd, 2000);
    ASSERT_GE(r.size(), 9u) << i;
    exceptions += (r[7] & 0x80) != 0;
  }
  ::close(fd);
  EXPECT_EQ(exceptions, 2000);
  expect_served("MalformedRequestsChangeNothing");
  expect_flat("MalformedRequestsChangeNothing");
}

}  // namespace
