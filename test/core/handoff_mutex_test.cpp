// The PLC's lock in a virtual-time run: the run keeps it from scan to scan, and a client
// that waits has it between two scans (core/handoff_mutex.h).
#include <gtest/gtest.h>

#include <thread>

#include "plc_cell/core/handoff_mutex.h"
#include "plc_cell/core/plc.h"

using namespace plc_cell;

namespace {

// Until `count()` reaches n, or a bounded number of yields: a client thread counts as
// waiting once it is inside lock().
template <class F>
bool await(F count, uint64_t n) {
  for (int i = 0; i < 50000000 && count() < n; ++i) std::this_thread::yield();
  return count() == n;
}

}  // namespace

TEST(HandoffMutex, AWaitingClientHasTheLockBetweenTheNextTwoSteps) {
  HandoffMutex mu;
  int step = 0, client_saw = -1;
  std::thread client;
  {
    std::lock_guard<HandoffMutex> holder(mu);
    for (step = 1; step <= 10; ++step) {
      if (step == 3) {
        client = std::thread([&] {
          std::lock_guard<HandoffMutex> lk(mu);
          client_saw = step;
        });
        EXPECT_TRUE(await([&] { return mu.waiting(); }, 1));
      }
      mu.let_waiters_in();
    }
  }
  client.join();
  EXPECT_EQ(client_saw, 3);  // not after the holder's last step (11): in at the first chance
  EXPECT_EQ(mu.waiting(), 0u);
}

TEST(HandoffMutex, EachStepLetsAtLeastOneOfSeveralWaitersIn) {
  HandoffMutex mu;
  int step = 0, saw[2] = {-1, -1};
  std::thread clients[2];
  {
    std::lock_guard<HandoffMutex> holder(mu);
    for (step = 1; step <= 10; ++step) {
      if (step == 3) {
        for (int k = 0; k < 2; ++k)
          clients[k] = std::thread([&, k] {
            std::lock_guard<HandoffMutex> lk(mu);
            saw[k] = step;
          });
        EXPECT_TRUE(await([&] { return mu.waiting(); }, 2));
      }
      mu.let_waiters_in();
    }
  }
  for (auto& c : clients) c.join();
  for (int k = 0; k < 2; ++k) {
    EXPECT_GE(saw[k], 3);
    EXPECT_LE(saw[k], 4);  // one at step 3 at least, the other by step 4
  }
}

TEST(HandoffMutex, WithNobodyWaitingTheHolderKeepsTheLock) {
  HandoffMutex mu;
  std::lock_guard<HandoffMutex> holder(mu);
  for (int step = 0; step < 1000; ++step) mu.let_waiters_in();
  EXPECT_EQ(mu.waiting(), 0u);
}

TEST(HandoffMutex, APlcClientReadsBetweenTwoScansOfAVirtualRun) {
  Plc plc;
  plc.load_program_text("ORG M1925\nINC R0\nEND\n", "count.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  uint64_t now_us = 0;
  uint32_t client_read = 0;
  std::thread client;
  plc.locked_steps([&](ScanEngine& e, Memory&) {
    e.scan(now_us);
    now_us += 1000;
    if (e.stats().scans == 5) {
      client = std::thread([&] { client_read = plc.read(parse_address("R0"), 1).at(0); });
      EXPECT_TRUE(await([&] { return plc.waiting_clients(); }, 1));
    }
    return e.stats().scans < 20;
  });
  client.join();
  EXPECT_EQ(client_read, 5u);  // the count of five scans, not of twenty
  EXPECT_EQ(plc.read(parse_address("R0"), 1).at(0), 20u);
}
