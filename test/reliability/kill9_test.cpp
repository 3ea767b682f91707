// kill -9 of `plc_cell run` at random moments while a client writes: after a restart
// every acknowledged write and every value the program latched is still there.
#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include <atomic>
#include <cstdio>
#include <fstream>
#include <functional>
#include <random>
#include <thread>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/client.h"
#include "kill9_loop.h"
#include "run_child.h"
#include "temp_dir.h"

using namespace plc_cell;

namespace {

constexpr int kRegs = 50;           // the client writes D0..D49
constexpr uint32_t kCounter = 200;  // the program counts D200 up every scan

// A writer: write D[k] = v, read D200; throws on any failure (= not acknowledged).
struct Writer {
  std::function<void(int, uint16_t)> write;
  std::function<uint16_t(int)> read;
};

Writer fatek_writer(fatek::Client* c) {
  return {[c](int k, uint16_t v) { c->write(Address{Area::D, Width::Word, uint32_t(k)}, {v}); },
          [c](int k) { return uint16_t(c->read(Address{Area::D, Width::Word, uint32_t(k)}, 1)[0]); }};
}

struct ModbusConn {
  explicit ModbusConn(int port) : ctx(modbus_new_tcp("127.0.0.1", port)) {
    if (!ctx || modbus_connect(ctx) != 0) throw std::runtime_error("modbus connect");
    modbus_set_response_timeout(ctx, 2, 0);
  }
  ~ModbusConn() {
    modbus_close(ctx);
    modbus_free(ctx);
  }
  modbus_t* ctx;
};

Writer modbus_writer(ModbusConn* m) {
  // D0.. is holding register 6000.. in the default map.
  return {[m](int k, uint16_t v) {
            if (modbus_write_register(m->ctx, 6000 + k, v) != 1) throw std::runtime_error("modbus write");
          },
          [m](int k) {
            uint16_t v;
            if (modbus_read_registers(m->ctx, 6000 + k, 1, &v) != 1) throw std::runtime_error("modbus read");
            return v;
          }};
}

class Kill9 : public ::testing::TestWithParam<bool> {  // param: true = Modbus, false = FATEK
 protected:
  void SetUp() override {
    const std::string prog = dir_.path() + "/count.il";
    std::ofstream(prog) << "ORG M1925\nINC D=D200\nEND\n";
    const std::string cfg = dir_.path() + "/cell.yaml";
    std::ofstream(cfg) << "cell: {name: k9, program: count.il}\n"
                          "plc: {scan_period: 0.001, retentive: [D0-D299], persist: store.bin}\n";
    args_ = {"--config", cfg, GetParam() ? "--modbus-tcp" : "--fatek-tcp", "127.0.0.1:0"};
  }
  // Runs one client session against a fresh child until `kill_after` acknowledged writes,
  // when another thread kills the child mid-traffic.
  void session(std::mt19937& rng, int round, std::vector<int>* expected, int* maybe_k, int* maybe_v,
               uint16_t* counter_seen) {
    RunChild child(args_);
    std::unique_ptr<fatek::Client> fc;
    std::unique_ptr<ModbusConn> mc;
    Writer w;
    if (GetParam()) {
      mc = std::make_unique<ModbusConn>(child.ports.at(0));
      w = modbus_writer(mc.get());
    } else {
      fatek::ClientOptions o;
      o.retries = 0;
      fc = std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(child.ports.at(0))), o);
      w = fatek_writer(fc.get());
    }
    verify(w, *expected, *maybe_k, *maybe_v, *counter_seen);
    *maybe_k = -1;
    const int kill_after = std::uniform_int_distribution<int>(1, 40)(rng);
    std::atomic<int> acked{0};
    std::thread killer([&] {
      // Busy-waits on the client's progress (not on time): the kill lands mid-traffic.
      while (acked.load() < kill_after) std::this_thread::yield();
      child.kill9();
    });
    for (int i = 0;; ++i) {
      const int k = std::uniform_int_distribution<int>(0, kRegs - 1)(rng);
      const uint16_t v = uint16_t(round * 1000 + i);
      *maybe_k = k;  // in flight: may or may not have been applied
      *maybe_v = v;
      try {
        w.write(k, v);
      } catch (const std::exception&) {
        break;
      }
      (*expected)[k] = v;
      *maybe_k = -1;
      try {
        *counter_seen = std::max(*counter_seen, w.read(kCounter));
      } catch (const std::exception&) {
        break;
      }
      ++acked;
    }
    killer.join();
  }
  // The write in flight at the kill may or may not have happened: from now on it is what was read.
  void verify(const Writer& w, std::vector<int>& expected, int maybe_k, int maybe_v, uint16_t counter_seen) {
    for (int k = 0; k < kRegs; ++k) {
      const int got = w.read(k);
      if (k == maybe_k) {
        EXPECT_TRUE(got == expected[k] || got == maybe_v) << "D" << k << " = " << got;
        expected[k] = got;
      } else {
        EXPECT_EQ(got, expected[k]) << "D" << k << ": an acknowledged write was lost";
      }
    }
    // Latched by the program before the kill (a client saw it) survives too.
    EXPECT_GE(w.read(kCounter), counter_seen);
  }

  TempDir dir_;
  std::vector<std::string> args_;
};

TEST_P(Kill9, AcknowledgedWritesAndLatchedValuesSurvive) {
  std::mt19937 rng(GetParam() ? 0x5eed : 0xfa7e);
  std::vector<int> expected(kRegs, 0);
  int maybe_k = -1, maybe_v = 0;
  uint16_t counter_seen = 0;
  for (int round = 1; round <= 6; ++round) session(rng, round, &expected, &maybe_k, &maybe_v, &counter_seen);
  // A last start checks the last round.
  RunChild child(args_);
  std::unique_ptr<fatek::Client> fc;
  std::unique_ptr<ModbusConn> mc;
  Writer w;
  if (GetParam()) {
    mc = std::make_unique<ModbusConn>(child.ports.at(0));
    w = modbus_writer(mc.get());
  } else {
    fc = std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(child.ports.at(0))));
    w = fatek_writer(fc.get());
  }
  verify(w, expected, maybe_k, maybe_v, counter_seen);
  EXPECT_GT(counter_seen, 0);
  EXPECT_NE(child.log.find("persist: restored"), std::string::npos) << child.log;
}

INSTANTIATE_TEST_SUITE_P(Protocols, Kill9, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& i) { return i.param ? "Modbus" : "Fatek"; });

}  // namespace

// 60 kills while FATEK, libmodbus and mbpoll write at once (test/reliability/kill9_loop.h);
// every tenth start also finds its main file truncated or its live file's newest slot corrupt.
TEST(Kill9Mixed, SixtyKillsLoseNoAcknowledgedWrite) {
  TempDir dir;
  kill9::Loop loop(dir.path(), 0x6b696c6c);
  for (int i = 0; i < 60; ++i) loop.round();
  const std::string log = loop.finish();
  const kill9::Stats& s = loop.stats;
  for (const auto& e : s.errors) ADD_FAILURE() << e;
  EXPECT_EQ(s.kills, 60);
  EXPECT_EQ(s.lost, 0);
  EXPECT_GT(s.acked[0], 0);  // FATEK
  EXPECT_GT(s.acked[1], 0);  // libmodbus
  EXPECT_GT(s.acked[2], 0);  // mbpoll
  EXPECT_EQ(s.truncated_main, 12);
  EXPECT_GT(s.corrupt_live, 0);
  EXPECT_EQ(s.fallbacks_logged, s.truncated_main + s.corrupt_live);
  EXPECT_NE(log.find("persist: restored"), std::string::npos) << log;
  RecordProperty("kills", s.kills);
  RecordProperty("acknowledged_writes", int(s.total_acked()));
  RecordProperty("lost", int(s.lost));
  std::printf("kill -9: %d kills, %ld acknowledged writes (FATEK %ld, libmodbus %ld, mbpoll %ld), %ld lost; "
              "%d truncated main files, %d corrupt live slots\n",
              s.kills, s.total_acked(), s.acked[0], s.acked[1], s.acked[2], s.lost, s.truncated_main, s.corrupt_live);
}
