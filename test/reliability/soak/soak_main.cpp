// make soak: `plc_cell run` with FATEK and Modbus TCP servers and persistence, hammered for
// a bounded time by clients that check what they read, while a fault thread sends garbage,
// cuts frames mid-way and opens more connections than allowed. Reports requests, errors,
// mismatches, the server's memory growth and scan overruns, and the latency a well-behaved
// reader sees meanwhile (p99 and maximum: figures, not a pass condition, since they follow
// the machine's load). Exit 1 on any mismatch or death.
#include <arpa/inet.h>
#include <modbus/modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <thread>
#include <vector>

#include "../kill9_loop.h"
#include "../run_child.h"
#include "../temp_dir.h"
#include "plc_cell/core/address.h"
#include "plc_cell/fatek/client.h"

using namespace plc_cell;
using Clock = std::chrono::steady_clock;

namespace {

std::atomic<bool> g_stop{false};
std::atomic<uint64_t> fatek_ok{0}, fatek_err{0}, modbus_ok{0}, modbus_err{0}, mismatches{0}, faults{0};

long rss_kb(pid_t pid) {
  std::ifstream f("/proc/" + std::to_string(pid) + "/status");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

int raw_connect(int port) {
  const int fd = ::socket(AF_INET, SOCK_STREAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(uint16_t(port));
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (::connect(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) != 0) {
    ::close(fd);
    return -1;
  }
  return fd;
}

// Each FATEK client owns D(100*id)..+49: what it reads back must be what it wrote.
void fatek_client(int port, int id) {
  std::mt19937 rng(id);
  std::unique_ptr<fatek::Client> c;
  std::vector<uint32_t> mine(50, 0);
  bool known = false;
  while (!g_stop) {
    try {
      if (!c) {
        fatek::ClientOptions o;
        o.retries = 0;
        c = std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(port)), o);
      }
      const uint32_t k = rng() % 50, v = rng() & 0xFFFF;
      c->write(Address{Area::D, Width::Word, 100u * id + k}, {v});
      mine[k] = v;
      const auto got = c->read(Address{Area::D, Width::Word, 100u * id}, 50);
      if (known && got != mine) ++mismatches;
      known = true;
      fatek_ok += 2;
    } catch (const std::exception&) {
      ++fatek_err;
      c.reset();
      known = false;  // the write in flight may or may not have happened
      for (auto& m : mine) m = 0;
      try {
        fatek::ClientOptions o;
        auto z = std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(port)), o);
        z->write(Address{Area::D, Width::Word, 100u * id}, std::vector<uint32_t>(50, 0));
        known = true;
      } catch (const std::exception&) {
      }
    }
  }
}

// Each Modbus client owns D(1000 + 100*id).. (holding registers 7000 + 100*id..).
void modbus_client(int port, int id) {
  std::mt19937 rng(100 + id);
  modbus_t* ctx = nullptr;
  std::vector<uint16_t> mine(50, 0), got(50);
  while (!g_stop) {
    if (!ctx) {
      ctx = modbus_new_tcp("127.0.0.1", port);
      if (modbus_connect(ctx) != 0 || modbus_write_registers(ctx, 7000 + 100 * id, 50, mine.data()) != 50) {
        ++modbus_err;
        modbus_free(ctx);
        ctx = nullptr;
        continue;
      }
    }
    const int k = int(rng() % 50);
    const uint16_t v = uint16_t(rng());
    if (modbus_write_register(ctx, 7000 + 100 * id + k, v) != 1 ||
        modbus_read_registers(ctx, 7000 + 100 * id, 50, got.data()) != 50) {
      ++modbus_err;
      modbus_close(ctx);
      modbus_free(ctx);
      ctx = nullptr;
      continue;
    }
    mine[size_t(k)] = v;
    if (got != mine) ++mismatches;
    modbus_ok += 2;
  }
  if (ctx) {
    modbus_close(ctx);
    modbus_free(ctx);
  }
}

// A well-behaved reader beside the abuse: one Modbus and one FATEK read of 10 registers
// at a time, each timed. The latency figures of the hostile-client tests live here.
std::vector<double> modbus_ms, fatek_ms;

void latency_probe(int fatek_port, int modbus_port) {
  modbus_t* ctx = modbus_new_tcp("127.0.0.1", modbus_port);
  const bool mb_ok = modbus_connect(ctx) == 0;
  std::unique_ptr<fatek::Client> c;
  uint16_t regs[10];
  while (!g_stop) {
    auto t0 = Clock::now();
    if (mb_ok && modbus_read_registers(ctx, 0, 10, regs) == 10)
      modbus_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    try {
      if (!c) c = std::make_unique<fatek::Client>(fatek::tcp_transport("127.0.0.1:" + std::to_string(fatek_port)));
      t0 = Clock::now();
      c->read(Address{Area::R, Width::Word, 0}, 10);
      fatek_ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    } catch (const std::exception&) {
      c.reset();
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));  // the probe's pace
  }
  modbus_close(ctx);
  modbus_free(ctx);
}

std::string latency(std::vector<double> v) {
  if (v.empty()) return "no reply";
  std::sort(v.begin(), v.end());
  char b[96];
  std::snprintf(b, sizeof b, "%zu reads, p99 %.2f ms, max %.2f ms", v.size(),
                v[std::min(v.size() - 1, size_t(double(v.size()) * 0.99))], v.back());
  return b;
}

void fault_thread(int fatek_port, int modbus_port) {
  std::mt19937 rng(7);
  while (!g_stop) {
    const int port = rng() & 1 ? fatek_port : modbus_port;
    switch (rng() % 3) {
      case 0: {  // garbage, then vanish
        const int fd = raw_connect(port);
        if (fd >= 0) {
          std::string g(64 + rng() % 200, '\0');
          for (auto& ch : g) ch = char(rng());
          (void)!::send(fd, g.data(), g.size(), MSG_NOSIGNAL);
          ::close(fd);
        }
        break;
      }
      case 1: {  // half a frame, then vanish
        const int fd = raw_connect(port);
        if (fd >= 0) {
          const char* half = port == fatek_port ? "\x02" "0146" : "\x00\x01\x00\x00\x00\x06\x01\x03";
          (void)!::send(fd, half, port == fatek_port ? 5 : 8, MSG_NOSIGNAL);
          ::close(fd);
        }
        break;
      }
      case 2: {  // more connections than allowed
        std::vector<int> fds;
        for (int i = 0; i < 24; ++i) fds.push_back(raw_connect(port));
        for (int fd : fds)
          if (fd >= 0) ::close(fd);
        break;
      }
    }
    ++faults;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));  // fault rate
  }
}

}  // namespace

int main(int argc, char** argv) {
  const int seconds = argc > 1 ? std::atoi(argv[1]) : 60;
  TempDir dir;
  std::ofstream(dir.path() + "/soak.il") << "ORG M1925\nINC D=D50\nMOV S=D50 D=R50\nEND\n";
  std::ofstream(dir.path() + "/soak.yaml") << "cell: {name: soak, program: soak.il}\n"
                                              "plc: {scan_period: 0.001, persist: store.bin}\n";
  RunChild child({"--config", dir.path() + "/soak.yaml", "--fatek-tcp", "127.0.0.1:0", "--modbus-tcp", "127.0.0.1:0"}, 2);
  const int fport = child.ports.at(0), mport = child.ports.at(1);
  std::vector<std::thread> ts;
  for (int i = 0; i < 2; ++i) ts.emplace_back(fatek_client, fport, i);
  for (int i = 0; i < 2; ++i) ts.emplace_back(modbus_client, mport, i);
  ts.emplace_back(fault_thread, fport, mport);
  ts.emplace_back(latency_probe, fport, mport);
  const auto t0 = Clock::now();
  std::this_thread::sleep_for(std::chrono::seconds(std::min(5, std::max(1, seconds / 10))));  // warm-up
  const long rss0 = rss_kb(child.pid());
  std::this_thread::sleep_for(std::chrono::seconds(seconds) - (Clock::now() - t0));
  const long rss1 = rss_kb(child.pid());
  g_stop = true;
  for (auto& t : ts) t.join();
  const double secs = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::string log = child.terminate();
  std::string summary, line;  // "plc_cell run: N scans, cycle avg ... overruns N"
  std::istringstream lines(log);
  while (std::getline(lines, line))
    if (line.find(" scans, cycle avg") != std::string::npos) summary = line;
  std::printf("soak: %.0f s, FATEK %llu requests (%.0f/s) %llu errors, Modbus %llu requests (%.0f/s) %llu errors\n", secs,
              (unsigned long long)fatek_ok, fatek_ok / secs, (unsigned long long)fatek_err, (unsigned long long)modbus_ok,
              modbus_ok / secs, (unsigned long long)modbus_err);
  std::printf("soak: %llu faults injected, %llu read-back mismatches\n", (unsigned long long)faults,
              (unsigned long long)mismatches);
  std::printf("soak: server RSS %ld kB after warm-up, %ld kB at the end (growth %ld kB)\n", rss0, rss1, rss1 - rss0);
  std::printf("soak: %s\n", summary.empty() ? "(no summary from plc_cell run)" : summary.c_str());
  std::printf("soak: a well-behaved reader meanwhile: Modbus %s; FATEK %s\n", latency(modbus_ms).c_str(),
              latency(fatek_ms).c_str());
  // Second phase: kill -9 at random moments under three writers (kill9_loop.h), as many
  // rounds as fit in the same time again, at least 100.
  TempDir kdir;
  kill9::Loop k9(kdir.path(), 0x736f616b);
  const auto k0 = Clock::now();
  while (k9.stats.kills < 100 || Clock::now() - k0 < std::chrono::seconds(seconds)) k9.round();
  k9.finish();
  const kill9::Stats& ks = k9.stats;
  std::printf("soak: kill -9: %d kills, %ld acknowledged writes (FATEK %ld, libmodbus %ld, mbpoll %ld), %ld lost; "
              "%d truncated main files, %d corrupt live slots, %d fallbacks reported\n",
              ks.kills, ks.total_acked(), ks.acked[0], ks.acked[1], ks.acked[2], ks.lost, ks.truncated_main,
              ks.corrupt_live, ks.fallbacks_logged);
  for (const auto& e : ks.errors) std::printf("soak: kill -9: %s\n", e.c_str());
  const bool ok = mismatches == 0 && !summary.empty() && fatek_ok > 0 && modbus_ok > 0 && ks.lost == 0 &&
                  ks.errors.empty() && ks.fallbacks_logged == ks.truncated_main + ks.corrupt_live;
  std::printf("soak: %s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
