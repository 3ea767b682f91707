// FATEK benchmarks (docs/fatek.md "Performance"):
//  - codec: encode + decode of a 64-register cmd 46 response frame (and its request);
//  - TCP loopback, one client, cmd 46 reading 64 registers: req/s, p50/p99 latency,
//    against libmodbus's own TCP server reading 64 holding registers in the same run;
//  - serial at 921600 baud over a socat pty: one poll cycle vs the line-rate bound.
#include <benchmark/benchmark.h>
#include <arpa/inet.h>
#include <modbus.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <optional>
#include <thread>
#include <vector>

#include "../test/harness/pty_pair.h"
#include "latency_counters.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/server.h"

using namespace plc_cell;
using namespace plc_cell::fatek;
using Clock = std::chrono::steady_clock;

static void BM_CodecEncodeDecode64(benchmark::State& st) {
  Request req;
  req.cmd = Cmd::ReadRegisters;
  req.start = parse_address("R0");
  req.count = 64;
  Response rsp;
  for (uint32_t i = 0; i < 64; ++i) rsp.values.push_back(i * 977);
  std::string wire;
  wire.reserve(kMaxFrame);
  Decoder dec;
  Response back;
  back.values.reserve(64);
  std::string why;
  for (auto _ : st) {
    wire.clear();
    append_response(wire, req, rsp);
    dec.feed(reinterpret_cast<const uint8_t*>(wire.data()), wire.size(),
             [&](const Frame& f) { parse_response(req, f, &back, &why); }, [](Decoder::Fault) {});
    benchmark::DoNotOptimize(back.values.data());
  }
  st.counters["frame_bytes"] = double(wire.size());
}
BENCHMARK(BM_CodecEncodeDecode64);

static void BM_FatekTcp46x64(benchmark::State& st) {
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  TcpServer server(plc, o);
  server.start();
  ClientOptions co;
  co.timeout_ms = 2000;
  Client c(tcp_transport("127.0.0.1:" + std::to_string(server.port())), co);
  const Address r0 = parse_address("R0");
  std::vector<double> us;
  for (auto _ : st) {
    const auto t0 = Clock::now();
    auto v = c.read(r0, 64);
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
    benchmark::DoNotOptimize(v.data());
  }
  latency_counters(st, us);
  server.stop();
}
BENCHMARK(BM_FatekTcp46x64)->UseRealTime()->MinTime(2.0);

// libmodbus reference: its own TCP server (modbus_receive + modbus_reply) on a thread.
static void BM_LibmodbusTcp03x64(benchmark::State& st) {
  modbus_mapping_t* map = modbus_mapping_new(0, 0, 1000, 0);
  modbus_t* srv = modbus_new_tcp("127.0.0.1", 0);
  int ls = modbus_tcp_listen(srv, 1);
  sockaddr_in sa{};
  socklen_t len = sizeof sa;
  getsockname(ls, reinterpret_cast<sockaddr*>(&sa), &len);
  const int port = ntohs(sa.sin_port);
  std::thread th([&] {
    modbus_tcp_accept(srv, &ls);
    uint8_t q[MODBUS_TCP_MAX_ADU_LENGTH];
    for (;;) {
      const int n = modbus_receive(srv, q);
      if (n > 0) modbus_reply(srv, q, n, map);
      else if (n == -1) break;  // client closed
    }
  });
  modbus_t* cli = modbus_new_tcp("127.0.0.1", port);
  if (modbus_connect(cli) != 0) {
    st.SkipWithError("libmodbus connect failed");
  }
  uint16_t regs[64];
  std::vector<double> us;
  for (auto _ : st) {
    const auto t0 = Clock::now();
    if (modbus_read_registers(cli, 0, 64, regs) != 64) {
      st.SkipWithError("libmodbus read failed");
      break;
    }
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  latency_counters(st, us);
  modbus_close(cli);
  modbus_free(cli);
  th.join();
  ::close(ls);
  modbus_close(srv);
  modbus_free(srv);
  modbus_mapping_free(map);
}
BENCHMARK(BM_LibmodbusTcp03x64)->UseRealTime()->MinTime(2.0);

// Serial at 921600 baud 7E1 over a socat pty pair: one cmd 46 x 64 poll cycle.
// Line-rate bound: (16 request + 265 response bytes) x 10 bits / 921600 baud = 3.05 ms.
// A pty does not pace bytes at the baud rate, so the cycle measures the software path.
static void BM_FatekSerialPty46x64(benchmark::State& st) {
  char dir[] = "/tmp/fatek_bench_XXXXXX";
  if (!::mkdtemp(dir)) {
    st.SkipWithError("mkdtemp");
    return;
  }
  // The pair is stopped on the way out of this scope, whatever throws in it.
  std::optional<plc_cell::testing::PtyPair> pty;
  try {
    pty.emplace(dir, "");
  } catch (const std::exception& e) {
    st.SkipWithError(e.what());
    return;
  }
  const std::string a = pty->a, b = pty->b;
  {
    Plc plc;
    SerialServerOptions so;
    so.line = parse_serial_settings(a + ":921600:7E1");
    SerialServer server(plc, so);
    server.start();
    ClientOptions co;
    co.timeout_ms = 2000;
    Client c(serial_transport(parse_serial_settings(b + ":921600:7E1")), co);
    const Address r0 = parse_address("R0");
    std::vector<double> us;
    for (auto _ : st) {
      const auto t0 = Clock::now();
      auto v = c.read(r0, 64);
      us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
      benchmark::DoNotOptimize(v.data());
    }
    latency_counters(st, us);
    const double bytes = 16 + (1 + 2 + 2 + 1 + 64 * 4 + 2 + 1);
    st.counters["line_bound_us"] = bytes * 10.0 / 921600.0 * 1e6;
    server.stop();
  }
  pty.reset();
  std::string rm = std::string("rm -rf ") + dir;
  if (std::system(rm.c_str()) != 0) st.SkipWithError("cleanup");
}
BENCHMARK(BM_FatekSerialPty46x64)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
