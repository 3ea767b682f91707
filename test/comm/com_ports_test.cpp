// COM ports with one owner: FUN150 and FUN151 on the same port share one line and one
// thread, so their transactions follow each other on the wire; `plc_cell check` opens no
// port at all.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <functional>
#include <future>
#include <mutex>
#include <string>
#include <thread>

#include "../fatek/fatek_link.h"
#include "plc_cell/comm/protocol_functions.h"
#include "plc_cell/fatek/frame.h"
#include "plc_cell/fatek/serial_port.h"
#include "plc_cell/fatek/slave.h"
#include "plc_cell/io/com_port.h"
#include "plc_cell/io/serial_line.h"
#include "plc_cell/modbus/rtu_frame.h"
#include "plc_cell/modbus/slave_handler.h"
#include "plc_cell/sim/soft_cell.h"

using namespace plc_cell;

namespace {

CellExtensions protocol(bool open_ports) {
  CellExtensions x;
  x.push_back(std::make_unique<ProtocolFunctions>(open_ports));
  return x;
}

std::string write_file(const std::string& name, const std::string& text) {
  const std::string path = "/tmp/plc_cell_com_ports_" + name;
  std::ofstream(path) << text;
  return path;
}

uint32_t get(Plc& plc, const char* a) { return plc.read(parse_address(a), 1)[0]; }

// The far end of one serial line, answering FATEK frames (station 5) and Modbus RTU
// requests (slave 1) from one PLC's memory. It keeps the order requests came in and
// counts any byte that arrives while a request is still unanswered: a line with two
// owners would interleave there.
class TwoProtocolPeer {
 public:
  TwoProtocolPeer(Plc& plc, const std::string& device) : plc_(plc), fatek_(plc, 5) {
    fd_ = open_serial_line(parse_serial_settings(device + ":115200:8N1"));
    thread_ = std::thread([this] { run(); });
  }
  ~TwoProtocolPeer() {
    stop_ = true;
    thread_.join();
    ::close(fd_);
  }
  std::string order() {
    std::lock_guard<std::mutex> lk(mu_);
    return order_;
  }
  int overlaps() const { return overlaps_; }

 private:
  void read_some(std::string* buf, int timeout_ms) {
    char b[256];
    if (!fatek::wait_readable(fd_, timeout_ms)) return;
    const ssize_t n = ::read(fd_, b, sizeof b);
    if (n > 0) buf->append(b, size_t(n));
  }
  // Bytes a Modbus RTU request of this function code needs (0: not known yet).
  static size_t rtu_length(const std::string& b) {
    if (b.size() < 2) return 0;
    const uint8_t fc = uint8_t(b[1]);
    if (fc == 15 || fc == 16) return b.size() < 7 ? 0 : 9 + size_t(uint8_t(b[6]));
    return 8;
  }
  void answer(const std::string& reply, char kind) {
    // Give a second owner of the line every chance to talk over this request.
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::string extra;
    read_some(&extra, 0);
    if (!extra.empty()) ++overlaps_;
    {
      std::lock_guard<std::mutex> lk(mu_);
      order_.push_back(kind);
    }
    fatek::write_all(fd_, reply.data(), reply.size(), 1000);
  }
  void run() {
    std::string buf;
    while (!stop_) {
      read_some(&buf, 20);
      if (buf.empty()) continue;
      if (buf[0] == 0x02) {  // FATEK: STX .. ETX
        const size_t etx = buf.find('\x03');
        if (etx == std::string::npos) continue;
        if (etx + 1 != buf.size()) ++overlaps_;
        fatek::Decoder d;
        std::string out;
        for (size_t i = 0; i <= etx; ++i)
          if (d.push(uint8_t(buf[i])) == fatek::Decoder::Status::Frame) fatek_.handle(d.frame(), out);
        buf.clear();
        answer(out, 'F');
      } else {  // Modbus RTU, slave 1
        const size_t n = rtu_length(buf);
        if (n == 0 || buf.size() < n) continue;
        if (buf.size() != n) ++overlaps_;
        uint8_t rsp[300], adu[310];
        const modbus::PduAnswer a =
            modbus::answer_pdu(plc_, reinterpret_cast<const uint8_t*>(buf.data()) + 1, int(n) - 3, rsp);
        const int len = modbus::rtu_adu(uint8_t(buf[0]), rsp, a.length, adu);
        buf.clear();
        answer(std::string(reinterpret_cast<char*>(adu), size_t(len)), 'M');
      }
    }
  }

  Plc& plc_;
  fatek::Slave fatek_;
  int fd_ = -1;
  std::atomic<bool> stop_{false};
  std::atomic<int> overlaps_{0};
  std::mutex mu_;
  std::string order_;
  std::thread thread_;
};

const char* kBothOnPort1 =
    "ORG M0\nLD M1\nLD M2\nFUN 151 Pt=1 MD=0 SR=R100 WR=R200 ACT=Y0 ERR=Y1 DN=Y2\n"
    "ORG M100\nLD M101\nLD M102\nFUN 150 Pt=1 SR=R300 WR=R400 ACT=M110 ERR=M111 DN=M112\nEND\n";

}  // namespace

TEST(ComPorts, Fun150AndFun151ShareOnePortOneTransactionAtATime) {
  // Both instructions on port 1, one pty: one line carries FATEK and Modbus RTU requests.
  fatek_test::TempDir dir;
  fatek_test::PtyPair pty(dir.path);
  Plc slave;
  slave.write(parse_address("R0"), {11, 22, 33});
  slave.write(parse_address("R7"), {1234, 5678});
  TwoProtocolPeer peer(slave, pty.b);
  const std::string prog = write_file("both.il", kBothOnPort1);
  const std::string cfg = write_file("both.yaml", "cell: {program: " + prog + "}\nports:\n  timeout: 2s\n  1: {serial: " +
                                                      pty.a + ":115200:8N1}\n");
  SoftCell cell(cfg, "", protocol(true));
  Plc& master = cell.plc();
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  // FUN151: one packet, read station 5's R0..R2 into R10..; FUN150: one transaction, read
  // slave 1's 4x reference 8 (R7) and the next into R20..
  master.write(parse_address("R100"), {1, 5, 1, 3, 12, 10, 12, 0});
  master.write(parse_address("R300"), {0xA550, 0x0701, 1, 1, 2, 12, 20, 4, 8});
  master.write(parse_address("M0"), {1});
  master.write(parse_address("M100"), {1});  // both start in the same scan
  // FUN151 comes first in the program and takes the port; FUN150 waits for it (WR+4 b0)
  // until FUN151's EN goes off after its first packet, as on an FBs-PLC.
  bool fatek_done = false, mbus_done = false, mbus_waited = false, ready_while_held = false;
  uint64_t now = 0;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!(fatek_done && mbus_done) && std::chrono::steady_clock::now() < deadline) {
    master.scan(now += 1000);
    if (!fatek_done) ready_while_held = ready_while_held || get(master, "M1960") == 1;
    mbus_waited = mbus_waited || (get(master, "R404") & 1) != 0;
    if (!fatek_done && get(master, "Y2") == 1) {
      fatek_done = true;
      master.write(parse_address("M0"), {0});
    }
    mbus_done = mbus_done || get(master, "M112") == 1;
    std::this_thread::yield();
  }
  ASSERT_TRUE(fatek_done);
  ASSERT_TRUE(mbus_done);
  EXPECT_TRUE(mbus_waited);
  EXPECT_FALSE(ready_while_held);  // M1960: port 1 busy for both instructions
  EXPECT_EQ(get(master, "M111"), 0u) << "FUN150 WR+0 = " << get(master, "R400");
  EXPECT_EQ(master.read(parse_address("R10"), 3), (std::vector<uint32_t>{11, 22, 33}));
  EXPECT_EQ(master.read(parse_address("R20"), 2), (std::vector<uint32_t>{1234, 5678}));
  const std::string order = peer.order();
  // On one line: FUN151's FATEK frames (the scan that turns EN off still sends the next
  // packet: the port is released after the transaction in flight), then FUN150's request.
  ASSERT_GE(order.size(), 2u) << order;
  EXPECT_EQ(order.find_first_not_of('F'), order.size() - 1) << order;
  EXPECT_EQ(order.back(), 'M') << order;
  EXPECT_EQ(peer.overlaps(), 0) << "a request went out while another was unanswered: " << order;
}

// The device goes away under both instructions and comes back at the same path: the port
// reopens it for whichever uses it next.
TEST(ComPorts, APortReopensItsSerialDeviceWhenItIsBack) {
  fatek_test::TempDir dir;
  auto pty = std::make_unique<fatek_test::PtyPair>(dir.path);
  const std::string device = pty->a;
  Plc slave;
  slave.write(parse_address("R0"), {11, 22, 33});
  slave.write(parse_address("R7"), {4242});
  auto peer = std::make_unique<TwoProtocolPeer>(slave, pty->b);
  const std::string prog = write_file("reopen.il", kBothOnPort1);
  const std::string cfg = write_file("reopen.yaml", "cell: {program: " + prog + "}\nports:\n  timeout: 300ms\n  1: {serial: " +
                                                        device + ":115200:8N1}\n");
  SoftCell cell(cfg, "", protocol(true));
  Plc& master = cell.plc();
  ASSERT_TRUE(master.set_mode(RunMode::Run));
  master.write(parse_address("R100"), {1, 5, 1, 3, 12, 10, 12, 0});
  master.write(parse_address("R300"), {0xA550, 0x0701, 1, 1, 1, 12, 20, 4, 8});
  uint64_t now = 0;
  const auto scan_until = [&](const std::function<bool()>& pred) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
    while (std::chrono::steady_clock::now() < deadline) {
      master.scan(now += 1000);
      if (pred()) return true;
      std::this_thread::yield();
    }
    return false;
  };
  // One FUN150 pass (EN 0 -> 1, scans until DN); true when it read R7 without error.
  const auto fun150 = [&] {
    master.write(parse_address("R20"), {0});
    master.write(parse_address("M100"), {1});
    const bool done = scan_until([&] { return get(master, "M112") == 1; });
    const bool ok = done && get(master, "M111") == 0 && get(master, "R20") == 4242;
    master.write(parse_address("M100"), {0});
    master.scan(now += 1000);
    return ok;
  };
  // One FUN151 packet (EN on until DN, then off until the port is free again).
  const auto fun151 = [&] {
    master.write(parse_address("R10"), {0});
    master.write(parse_address("M0"), {1});
    const bool done = scan_until([&] { return get(master, "Y2") == 1; });
    const bool ok = done && get(master, "Y1") == 0 && get(master, "R10") == 11;
    master.write(parse_address("M0"), {0});
    EXPECT_TRUE(scan_until([&] { return get(master, "M1960") == 1; }));
    return ok;
  };
  ASSERT_TRUE(fun150());
  ASSERT_TRUE(fun151());
  peer.reset();
  pty.reset();  // the device goes away
  EXPECT_FALSE(fun151());
  EXPECT_FALSE(fun151());  // still gone: the port cannot open it
  pty = std::make_unique<fatek_test::PtyPair>(dir.path);  // back at the same path
  peer = std::make_unique<TwoProtocolPeer>(slave, pty->b);
  bool back = false;
  for (int i = 0; i < 20 && !back; ++i) back = fun151();
  EXPECT_TRUE(back);
  EXPECT_TRUE(fun150());  // the same line, reopened once for both
  peer.reset();
}

TEST(ComPorts, APortRunsItsTransactionsOneAtATimeInTheOrderTheyCame) {
  ComPort port(1);
  std::promise<void> release_first;
  std::shared_future<void> first_may_end = release_first.get_future().share();
  std::mutex mu;
  std::string log;
  std::atomic<int> running{0}, most{0};
  std::promise<void> all_done;
  auto job = [&](char name, bool wait, bool last) {
    return [&, name, wait, last] {
      most = std::max(most.load(), ++running);
      {
        std::lock_guard<std::mutex> lk(mu);
        log += name;
      }
      if (wait) first_may_end.wait();  // still on the line while the others are submitted
      --running;
      if (last) all_done.set_value();
    };
  };
  port.submit(job('a', true, false));
  port.submit(job('b', false, false));
  port.submit(job('c', false, true));
  release_first.set_value();
  ASSERT_EQ(all_done.get_future().wait_for(std::chrono::seconds(10)), std::future_status::ready);
  EXPECT_EQ(log, "abc");
  EXPECT_EQ(most.load(), 1);
}

namespace {

// A listening loopback socket nobody has connected to yet.
struct Listener {
  Listener() {
    fd = ::socket(AF_INET, SOCK_STREAM | SOCK_NONBLOCK, 0);
    sockaddr_in a{};
    a.sin_family = AF_INET;
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a);
    ::listen(fd, 4);
    socklen_t len = sizeof a;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&a), &len);
    port = ntohs(a.sin_port);
  }
  ~Listener() { ::close(fd); }
  // Whether a connection came within timeout_ms (it is accepted and closed).
  bool connected(int timeout_ms) {
    pollfd p{fd, POLLIN, 0};
    if (::poll(&p, 1, timeout_ms) != 1) return false;
    const int c = ::accept(fd, nullptr, nullptr);
    if (c >= 0) ::close(c);
    return c >= 0;
  }
  int fd = -1;
  int port = 0;
};

}  // namespace

TEST(ComPorts, CheckOpensNoPortAndRunOpensEachOnce) {
  Listener tcp;
  const std::string prog = write_file("check.il", kBothOnPort1);
  // Port 2's device does not exist: check accepts the file all the same (it opens nothing).
  const std::string cfg = write_file("check.yaml", "cell: {program: " + prog + "}\nports:\n  1: {tcp: 127.0.0.1:" +
                                                       std::to_string(tcp.port) +
                                                       "}\n  2: {serial: /tmp/plc_cell_no_such_tty}\n"
                                                       "modbus:\n  ports:\n    1: {tcp: 127.0.0.1:" +
                                                       std::to_string(tcp.port) + "}\n");
  {
    SoftCell cell(cfg, "", protocol(false));
    Plc& plc = cell.plc();
    ASSERT_TRUE(plc.set_mode(RunMode::Run));
    plc.write(parse_address("R300"), {0xA550, 0x0701, 1, 1, 2, 12, 20, 4, 8});
    plc.write(parse_address("M100"), {1});
    plc.scan(1000);
    EXPECT_EQ(get(plc, "M111"), 1u);            // FUN150 is there, with no port behind it
    EXPECT_EQ(get(plc, "R400") >> 8, 7u);       // result 7: no such port
    EXPECT_FALSE(tcp.connected(0));
  }
  EXPECT_FALSE(tcp.connected(0));
  {
    SoftCell cell(cfg, "", protocol(true));  // port 1 declared twice, the same line: one connection
    EXPECT_TRUE(tcp.connected(5000));
    EXPECT_FALSE(tcp.connected(0));
  }
}
