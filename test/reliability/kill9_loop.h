#pragma once
// kill -9 of `plc_cell run` at random moments (fixed seed) while three clients write
// retentive registers at once: our FATEK client (D0-D19), libmodbus (D20-D39) and the
// third-party mbpoll (D40-D49), each on its own registers so every write has one order.
// Each acknowledged write is recorded; after every restart all of them must be there. The
// write in flight at the kill may or may not have happened: from then on it is what was read.
// Every few rounds the store is damaged after the kill (main file truncated, or the live
// file's newest slot corrupted): the documented fallback still holds every acknowledged write.
// Used by reliability_tests (bounded) and by `make soak` (longer); no gtest in here.
#include <modbus/modbus.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <fstream>
#include <iterator>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/persist/slot_file.h"
#include "run_child.h"

namespace kill9 {

constexpr int kRegs = 50;           // D0..D49 are written, D200 counts every scan
constexpr uint32_t kCounter = 200;

struct Stats {
  int kills = 0;
  long acked[3] = {0, 0, 0};  // FATEK, libmodbus, mbpoll
  long lost = 0;              // acknowledged writes missing after a restart
  int truncated_main = 0, corrupt_live = 0;  // store damages after a kill
  int fallbacks_logged = 0;                  // restarts whose log named the damage
  std::vector<std::string> errors;           // what went wrong, for the report
  long total_acked() const { return acked[0] + acked[1] + acked[2]; }
};

// One writer's registers: what was acknowledged and what is in flight.
struct Region {
  int first = 0, count = 0;
  std::vector<int> expected;
  int maybe_k = -1, maybe_v = 0;
};

inline std::string slurp(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
inline void spit(const std::string& p, const std::string& d) { std::ofstream(p, std::ios::binary | std::ios::trunc) << d; }

// mbpoll writes holding register `reg` (PDU address) = v; exit status 0 is its acknowledgement.
inline bool mbpoll_write(int port, int reg, int v) {
  const auto r = plc_cell::testing::run_process({"mbpoll", "-m", "tcp", "-p", std::to_string(port), "-a", "1", "-t",
                                                 "4", "-0", "-r", std::to_string(reg), "-1", "-o", "2", "-q",
                                                 "127.0.0.1", std::to_string(v)},
                                                30);
  return r.status == 0;
}

class Loop {
 public:
  Loop(const std::string& dir, uint32_t seed) : dir_(dir), rng_(seed) {
    std::ofstream(dir + "/count.il") << "ORG M1925\nINC D=D200\nEND\n";
    std::ofstream(dir + "/cell.yaml") << "cell: {name: k9, program: count.il}\n"
                                         "plc: {scan_period: 0.001, retentive: [D0-D299], persist: store.bin}\n";
    args_ = {"--config", dir + "/cell.yaml", "--fatek-tcp", "127.0.0.1:0", "--modbus-tcp", "127.0.0.1:0"};
    for (int w = 0; w < 3; ++w) {
      regions_[w].first = w * 20;
      regions_[w].count = w == 2 ? 10 : 20;
      regions_[w].expected.assign(size_t(regions_[w].count), 0);
    }
  }

  // One start: check everything acknowledged so far, write until a random number of
  // acknowledgements, kill -9 mid-traffic, maybe damage the store.
  void round() {
    const int n = ++round_;
    RunChild child(args_, 2);
    const int fport = child.ports.at(0), mport = child.ports.at(1);
    check(child, mport);
    std::atomic<long> acks{0};
    std::atomic<long> mbpoll_acks{0};  // this round's: a spawned mbpoll takes far longer than a frame
    std::atomic<bool> dead{false};
    const long kill_after = std::uniform_int_distribution<long>(1, 120)(rng_);
    const uint32_t seeds[3] = {uint32_t(rng_()), uint32_t(rng_()), uint32_t(rng_())};
    std::vector<std::thread> writers;
    for (int w = 0; w < 3; ++w)
      writers.emplace_back([&, w] {
        std::mt19937 r(seeds[w]);
        Region& g = regions_[w];
        std::unique_ptr<plc_cell::fatek::Client> fc;
        modbus_t* mb = nullptr;
        try {
          if (w == 0) {
            plc_cell::fatek::ClientOptions o;
            o.retries = 0;
            fc = std::make_unique<plc_cell::fatek::Client>(plc_cell::fatek::tcp_transport("127.0.0.1:" + std::to_string(fport)), o);
          } else if (w == 1) {
            mb = modbus_new_tcp("127.0.0.1", mport);
            if (!mb || modbus_connect(mb) != 0) throw std::runtime_error("connect");
            modbus_set_response_timeout(mb, 2, 0);
          }
        } catch (const std::exception&) {
          if (mb) modbus_free(mb);
          return;  // killed before this writer connected
        }
        for (int i = 0; !dead; ++i) {
          const int k = std::uniform_int_distribution<int>(0, g.count - 1)(r);
          const int v = (n * 97 + i * 13 + w) & 0x7FFF;
          g.maybe_k = k;
          g.maybe_v = v;
          bool ok = false;
          try {
            if (w == 0) {
              fc->write(plc_cell::Address{plc_cell::Area::D, plc_cell::Width::Word, uint32_t(g.first + k)}, {uint32_t(v)});
              ok = true;
            } else if (w == 1) {
              ok = modbus_write_register(mb, 6000 + g.first + k, uint16_t(v)) == 1;
            } else {
              ok = mbpoll_write(mport, 6000 + g.first + k, v);
            }
          } catch (const std::exception&) {
          }
          if (!ok) break;
          g.expected[size_t(k)] = v;
          g.maybe_k = -1;
          ++stats.acked[w];
          ++acks;
          if (w == 2) ++mbpoll_acks;
        }
        if (mb) {
          modbus_close(mb);
          modbus_free(mb);
        }
      });
    // Waits on the clients' progress, not on time; the bound only guards against writers that
    // all failed (then the round still kills and the next start checks what was acknowledged).
    const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    // Every fourth round also waits for an mbpoll acknowledgement: the in-process clients
    // reach kill_after long before one spawned mbpoll has answered, and the third-party
    // client's writes must be among those that survive the kills.
    const bool wait_mbpoll = n % 4 == 0;
    while ((acks.load() < kill_after || (wait_mbpoll && mbpoll_acks.load() == 0)) &&
           std::chrono::steady_clock::now() < give_up)
      std::this_thread::yield();
    if (acks.load() < kill_after) stats.errors.push_back("round " + std::to_string(n) + ": writers stalled at " + std::to_string(acks.load()) + " acknowledgements");
    child.kill9();
    dead = true;
    for (auto& t : writers) t.join();
    ++stats.kills;
    damage_ = 0;
    if (n % 5 == 0) truncate_main();
    if (n % 5 == 2) corrupt_newest_live_slot();
  }

  // A last start to check the last round; returns its log.
  std::string finish() {
    RunChild child(args_, 2);
    check(child, child.ports.at(1));
    return child.log;
  }

  Stats stats;

 private:
  void check(const RunChild& child, int mport) {
    // The damaged file is named in a problem line, and the start still restored a slot.
    const bool named = damage_ == 1 ? child.log.find("store.bin slot") != std::string::npos ||
                                          child.log.find("store.bin: ") != std::string::npos
                                    : child.log.find("store.bin.live slot") != std::string::npos;
    if (damage_ && named &&
        child.log.find("persist: restored") != std::string::npos)
      ++stats.fallbacks_logged;
    else if (damage_)
      stats.errors.push_back("round " + std::to_string(round_) + ": damaged store not reported:\n" + child.log);
    modbus_t* mb = modbus_new_tcp("127.0.0.1", mport);
    uint16_t got[kRegs];
    if (!mb || modbus_connect(mb) != 0 || modbus_read_registers(mb, 6000, kRegs, got) != kRegs) {
      stats.errors.push_back("round " + std::to_string(round_) + ": cannot read back after the restart");
      stats.lost += 1;
    } else {
      for (auto& g : regions_)
        for (int k = 0; k < g.count; ++k) {
          const int v = got[g.first + k];
          if (k == g.maybe_k && (v == g.maybe_v || v == g.expected[size_t(k)])) {
            g.expected[size_t(k)] = v;
          } else if (v != g.expected[size_t(k)]) {
            ++stats.lost;
            stats.errors.push_back("round " + std::to_string(round_) + ": D" + std::to_string(g.first + k) + " = " +
                                   std::to_string(v) + ", acknowledged " + std::to_string(g.expected[size_t(k)]));
          }
        }
      for (auto& g : regions_) g.maybe_k = -1;
    }
    if (mb) {
      modbus_close(mb);
      modbus_free(mb);
    }
  }
  void truncate_main() {
    const std::string f = dir_ + "/store.bin", d = slurp(f);
    spit(f, d.substr(0, d.size() / 2 + 7));
    ++stats.truncated_main;
    damage_ = 1;
  }
  void corrupt_newest_live_slot() {
    const std::string f = dir_ + "/store.bin.live";
    std::string d = slurp(f);
    std::vector<std::string> pr;
    const auto slots = plc_cell::persist::read_slots(f, &pr);
    if (slots.size() != 2) return;
    const int newest = slots[0].seq > slots[1].seq ? 0 : 1;
    d[(newest == 0 ? 0 : d.size() / 2) + 25] ^= 0x40;
    spit(f, d);
    ++stats.corrupt_live;
    damage_ = 2;
  }

  std::string dir_;
  std::mt19937 rng_;
  std::vector<std::string> args_;
  Region regions_[3];
  int round_ = 0, damage_ = 0;
};

}  // namespace kill9
