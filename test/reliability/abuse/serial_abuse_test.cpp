// Hostile bytes on the serial servers of `plc_cell run` (Modbus RTU and FATEK), each
// behind a pty proxy: line noise, frames cut mid-way, and a device that disappears
// and comes back. The process stays up, a well-behaved master keeps being answered,
// fds end where they began, and the scan has no watchdog fault. Waits are polls with
// deadlines.
#include <poll.h>

#include <chrono>
#include <fstream>
#include <random>

#include <gtest/gtest.h>

#include "../../modbus/wire.h"
#include "../pty_proxy.h"
#include "../run_child.h"
#include "../temp_dir.h"
#include "plc_cell/fatek/frame.h"
#include "proc_stats.h"

namespace {

using plc_cell::test::Bytes;
using Clock = std::chrono::steady_clock;

// One Modbus RTU read of R0..R3 by slave 1; true when a good reply came within timeout_ms.
bool rtu_probe(int fd, int timeout_ms = 1000) {
  if (!plc_cell::test::write_all(fd, plc_cell::test::rtu(1, {3, 0, 0, 0, 4}))) return false;
  const Bytes r = plc_cell::test::read_rtu_reply(fd, timeout_ms);
  return r.size() == 5 + 8 && r[1] == 3;
}

bool fatek_probe(int fd, int timeout_ms = 1000) {
  const std::string req = plc_cell::fatek::encode_frame(plc_cell::fatek::Frame{1, 0x46, "04R00000"});
  if (!plc_cell::test::write_all(fd, Bytes(req.begin(), req.end()))) return false;
  plc_cell::fatek::Decoder d;
  const auto end = Clock::now() + std::chrono::milliseconds(timeout_ms);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(end - Clock::now()).count();
    if (left <= 0) return false;
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, int(left)) <= 0) return false;
    uint8_t buf[256];
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n <= 0) return false;
    for (ssize_t i = 0; i < n; ++i)
      if (d.push(buf[i]) == plc_cell::fatek::Decoder::Status::Frame) return d.frame().data.rfind('0', 0) == 0;
  }
}

// Retries a probe until it succeeds or deadline_ms passes (a master retries too).
template <typename F>
bool served_within(F probe, int deadline_ms) {
  const auto end = Clock::now() + std::chrono::milliseconds(deadline_ms);
  while (Clock::now() < end)
    if (probe()) return true;
  return false;
}

TEST(SerialAbuse, NoiseCutFramesAndAVanishingDevice) {
  TempDir dir;
  std::ofstream(dir.path() + "/p.il") << "ORG X1\nOUT Y0\nEND\n";
  ::mkdir((dir.path() + "/mb").c_str(), 0700);
  ::mkdir((dir.path() + "/fk").c_str(), 0700);
  PtyProxy mb(dir.path() + "/mb", 1), fk(dir.path() + "/fk", 2);
  RunChild child({"--program", dir.path() + "/p.il", "--scan", "10ms", "--modbus-rtu", mb.device_link() + ":19200:8E1",
                  "--fatek-serial", fk.device_link() + ":9600:7E1", "--modbus-tcp", "127.0.0.1:0"},
                 1);
  const int m = plc_cell::test::open_raw_tty(mb.client_link()), f = plc_cell::test::open_raw_tty(fk.client_link());
  ASSERT_GE(m, 0);
  ASSERT_GE(f, 0);
  ASSERT_TRUE(served_within([&] { return rtu_probe(m); }, 5000)) << child.log;
  ASSERT_TRUE(served_within([&] { return fatek_probe(f); }, 5000)) << child.log;
  const int fds0 = abuse::fd_count(child.pid());

  std::mt19937 rng(3);
  int rtu_ok = 0, fatek_ok = 0;
  const int rounds = 30;
  for (int round = 0; round < rounds; ++round) {
    // Noise, then a frame cut mid-way, then a good request: the good one is answered.
    Bytes noise(1 + rng() % 64);
    for (auto& b : noise) b = uint8_t(rng());
    const Bytes good = plc_cell::test::rtu(1, {3, 0, 0, 0, 4});
    Bytes cut(good.begin(), good.begin() + 1 + long(rng() % 6));
    plc_cell::test::write_all(m, noise);
    plc_cell::test::write_all(m, cut);
    rtu_ok += served_within([&] { return rtu_probe(m, 300); }, 2000);
    std::string fnoise(size_t(1 + rng() % 64), 'x');
    for (auto& c : fnoise) c = char(rng() % 0x7F);
    const std::string fgood = plc_cell::fatek::encode_frame(plc_cell::fatek::Frame{1, 0x46, "04R00000"});
    fnoise += fgood.substr(0, 1 + rng() % 8);  // a FATEK frame cut mid-way
    plc_cell::test::write_all(f, Bytes(fnoise.begin(), fnoise.end()));
    fatek_ok += served_within([&] { return fatek_probe(f, 700); }, 3000);
  }
  EXPECT_EQ(rtu_ok, rounds);
  EXPECT_EQ(fatek_ok, rounds);
  std::printf("[ figures  ] serial noise: %d/%d RTU and %d/%d FATEK rounds served after noise + a cut frame\n", rtu_ok,
              rounds, fatek_ok, rounds);

  // The devices vanish and come back: the servers reopen them by path.
  for (int k = 0; k < 3; ++k) {
    mb.unplug();
    fk.unplug();
    EXPECT_FALSE(rtu_probe(m, 200));
    mb.replug();
    fk.replug();
    EXPECT_TRUE(served_within([&] { return rtu_probe(m, 300); }, 5000)) << "replug " << k;
    EXPECT_TRUE(served_within([&] { return fatek_probe(f, 500); }, 5000)) << "replug " << k;
  }
  // A reopened device may leave one more fd briefly; the count settles at the baseline.
  const auto end = Clock::now() + std::chrono::seconds(3);
  while (abuse::fd_count(child.pid()) > fds0 && Clock::now() < end) ::poll(nullptr, 0, 20);
  EXPECT_LE(abuse::fd_count(child.pid()), fds0);
  ::close(m);
  ::close(f);
  const std::string log = child.terminate();
  EXPECT_EQ(log.find("fault:"), std::string::npos) << log;
  EXPECT_NE(log.find(" scans, cycle avg"), std::string::npos) << log;
}

}  // namespace
