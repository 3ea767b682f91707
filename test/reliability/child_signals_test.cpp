// The processes tests start get the default signal actions and an empty mask, whatever the
// test runner inherited (a shell's background job ignores SIGINT), and every wait on them
// ends (test/harness/child_process.h).
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <string>

#include "../harness/child_process.h"
#include "run_child.h"
#include "temp_dir.h"

using plc_cell::testing::ChildProcess;
using plc_cell::testing::ChildTimeout;

namespace {

// What this process ignores and blocks while it lives, put back after.
class InheritedSignals {
 public:
  InheritedSignals() {
    for (int i = 0; i < kCount; ++i) saved_[i] = ::signal(kSignals[i], SIG_IGN) != SIG_ERR;
    sigset_t block;
    sigemptyset(&block);
    sigaddset(&block, SIGINT);
    sigaddset(&block, SIGTERM);
    ::pthread_sigmask(SIG_BLOCK, &block, &old_mask_);
  }
  ~InheritedSignals() {
    ::pthread_sigmask(SIG_SETMASK, &old_mask_, nullptr);
    for (int i = 0; i < kCount; ++i)
      if (saved_[i]) ::signal(kSignals[i], SIG_DFL);
  }
  static constexpr int kCount = 5;
  static constexpr int kSignals[kCount] = {SIGINT, SIGTERM, SIGQUIT, SIGHUP, SIGPIPE};

 private:
  bool saved_[kCount] = {};
  sigset_t old_mask_;
};

// The hex mask of one line of /proc/<pid>/status as the child itself printed it.
uint64_t mask(const std::string& status, const std::string& key) {
  const auto k = status.find(key + ":");
  if (k == std::string::npos) throw std::runtime_error("no " + key + " in:\n" + status);
  return std::stoull(status.substr(k + key.size() + 1), nullptr, 16);
}

TEST(ChildSignals, StartWithDefaultActionsAndNothingBlocked) {
  InheritedSignals inherited;
  ChildProcess child({"grep", "-E", "^Sig(Ign|Blk):", "/proc/self/status"});
  const int st = child.wait(std::chrono::seconds(30), "grep's exit");
  ASSERT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << child.output();
  const uint64_t ignored = mask(child.output(), "SigIgn"), blocked = mask(child.output(), "SigBlk");
  for (int s : InheritedSignals::kSignals) EXPECT_EQ(ignored >> (s - 1) & 1, 0u) << "signal " << s << " ignored";
  EXPECT_EQ(blocked, 0u) << child.output();
}

TEST(ChildSignals, SigintRightAfterTheSpawnStopsPlcCellRun) {
  // The clean-stop test's first moment, from a runner that ignores SIGINT: the child either
  // dies of the signal before it set up its stop handling or stops cleanly; it never runs on.
  TempDir dir;
  std::ofstream(dir.path() + "/count.il") << "ORG M1925\nINC D=D200\nEND\n";
  InheritedSignals inherited;
  for (int run = 0; run < 5; ++run) {
    RunChild child({"--program", dir.path() + "/count.il", "--fatek-tcp", "127.0.0.1:0"}, 0);
    const int st = child.stop(SIGINT);
    EXPECT_TRUE((WIFSIGNALED(st) && WTERMSIG(st) == SIGINT) || (WIFEXITED(st) && WEXITSTATUS(st) == 0))
        << "status " << st << "\n" << child.log;
  }
}

TEST(ChildSignals, AWaitPastItsBoundKillsTheChildAndSaysWhatItWaitedFor) {
  ChildProcess child({"sleep", "600"});
  const pid_t pid = child.pid();
  try {
    child.wait(std::chrono::milliseconds(200), "the end of a sleep");
    FAIL() << "the wait returned";
  } catch (const ChildTimeout& e) {
    EXPECT_NE(std::string(e.what()).find("waiting for the end of a sleep"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(child.running());
  EXPECT_NE(::kill(pid, 0), 0);  // reaped: no such process
}

TEST(ChildSignals, AShellCommandPastItsLimitFailsWithItsReason) {
  const auto r = plc_cell::testing::run_shell("echo started; sleep 600", 1);
  EXPECT_EQ(r.status, -1);
  EXPECT_NE(r.out.find("started"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no end after 1000 ms"), std::string::npos) << r.out;
}

}  // namespace
