// TRi host-link benchmarks (docs/tri.md "Performance"), each beside its FATEK peer in the
// same run, so that the ratio, not the machine, is the figure:
//  - codec: a 32-word RXI reply framed multi-point, stream-decoded, FCS checked and parsed,
//    against FATEK's cmd 46 reply of 32 registers;
//  - TCP loopback, one client: the smallest read (RVD, one DM word) against FATEK cmd 46 of
//    one register, and the largest (RXI, 32 words) against cmd 46 of 32 registers. The
//    client is the one tri_bridge and fatek_bridge use; the server is plc_cell run's.
#include <benchmark/benchmark.h>

#include <chrono>
#include <vector>

#include "latency_counters.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/tri/client.h"
#include "plc_cell/tri/commands.h"
#include "plc_cell/tri/frame.h"
#include "plc_cell/tri/server.h"

using namespace plc_cell;
using Clock = std::chrono::steady_clock;

namespace {

template <class Once>
void timed(benchmark::State& st, Once once) {
  std::vector<double> us;
  for (auto _ : st) {
    const auto t0 = Clock::now();
    once();
    us.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t0).count());
  }
  latency_counters(st, us);
}

tri::Request tri_request(const char* body) {
  tri::Request r;
  tri::parse_request(body, &r);
  return r;
}

}  // namespace

static void BM_TriCodecRxi32(benchmark::State& st) {
  const tri::Request req = tri_request("RXI000120");
  tri::Response rsp;
  for (uint32_t i = 0; i < 32; ++i) rsp.values.push_back(i * 977);
  tri::Frame f;
  f.multipoint = true;
  f.id = 1;
  tri::Response back;
  size_t bytes = 0;
  for (auto _ : st) {
    f.body = tri::encode_response(req, rsp);
    const std::string wire = tri::encode_frame(f);
    tri::Decoder dec(/*wildcard=*/false);
    dec.feed(wire, [&](const tri::Decoder::Event& e) { tri::parse_response(req, e.frame.body, &back); });
    benchmark::DoNotOptimize(back.values.data());
    bytes = wire.size();
  }
  st.counters["frame_bytes"] = double(bytes);
}
BENCHMARK(BM_TriCodecRxi32);

static void BM_FatekCodec46x32(benchmark::State& st) {
  fatek::Request req;
  req.cmd = fatek::Cmd::ReadRegisters;
  req.start = parse_address("R0");
  req.count = 32;
  fatek::Response rsp;
  for (uint32_t i = 0; i < 32; ++i) rsp.values.push_back(i * 977);
  std::string wire;
  fatek::Response back;
  std::string why;
  for (auto _ : st) {
    wire.clear();
    fatek::append_response(wire, req, rsp);
    fatek::Decoder dec;
    dec.feed(reinterpret_cast<const uint8_t*>(wire.data()), wire.size(),
             [&](const fatek::Frame& fr) { fatek::parse_response(req, fr, &back, &why); }, [](fatek::Decoder::Fault) {});
    benchmark::DoNotOptimize(back.values.data());
  }
  st.counters["frame_bytes"] = double(wire.size());
}
BENCHMARK(BM_FatekCodec46x32);

// The TRi side: the soft PLC's host-link server and tri_bridge's client, multi-point frames.
static void tri_tcp(benchmark::State& st, const char* body) {
  Plc plc;
  tri::TcpServer server(plc, "127.0.0.1", 0, tri::ServerOptions{});
  server.start();
  tri::ClientOptions co;
  co.timeout_ms = 2000;
  tri::Client c(tcp_transport("127.0.0.1:" + std::to_string(server.port())), co);
  const tri::Request req = tri_request(body);
  timed(st, [&] { benchmark::DoNotOptimize(c.transact(req).values.data()); });
  server.stop();
}

static void fatek_tcp(benchmark::State& st, int count) {
  Plc plc;
  fatek::TcpServerOptions o;
  o.port = 0;
  fatek::TcpServer server(plc, o);
  server.start();
  fatek::ClientOptions co;
  co.timeout_ms = 2000;
  fatek::Client c(tcp_transport("127.0.0.1:" + std::to_string(server.port())), co);
  const Address r0 = parse_address("R0");
  timed(st, [&] { benchmark::DoNotOptimize(c.read(r0, count).data()); });
  server.stop();
}

static void BM_TriTcpRvd(benchmark::State& st) { tri_tcp(st, "RVD0001"); }
static void BM_FatekTcp46x1(benchmark::State& st) { fatek_tcp(st, 1); }
static void BM_TriTcpRxi32(benchmark::State& st) { tri_tcp(st, "RXI000120"); }
static void BM_FatekTcp46x32(benchmark::State& st) { fatek_tcp(st, 32); }
BENCHMARK(BM_TriTcpRvd)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_FatekTcp46x1)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_TriTcpRxi32)->UseRealTime()->MinTime(2.0);
BENCHMARK(BM_FatekTcp46x32)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
