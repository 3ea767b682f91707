// Leaving the PLC as it was found, whatever stops the runner: a signal at random requests
// of a case (fixed seed), SIGKILL (the next run puts back what the journal holds), and a
// link that drops, garbles its replies or answers too late, where the case fails saying so
// and the restore waits for the link to come back. `plc_cell run` stands in for the PLC,
// behind a proxy that counts the requests and misbehaves on demand (fatek_proxy.h).
#include <sys/stat.h>

#include <cstdio>
#include <random>

#include "fatek_proxy.h"
#include "hardware_fixture.h"

namespace hardware_test {
namespace {

using plc_cell::parse_address;
using plc_cell::testing::ChildProcess;

const std::string kKill = kSource + "/test/hardware/kill.scenario.yaml";
const std::vector<std::string> kPoints = {"X0", "X1", "X3", "X4", "Y1", "M20", "M21", "R100", "D5", "RC0"};

class Killed : public HardwareTest {
 protected:
  Killed() : plc({"--config", kConveyor, "--no-simulation", "--fatek-tcp", "127.0.0.1:0"}) {
    // What someone left on the PLC: the part sensor forced ON, M20 forced OFF, values.
    plc_cell::fatek::Client c(plc_cell::fatek::tcp_transport(loopback(port())));
    c.control(parse_address("X3"), plc_cell::fatek::Action::Disable);
    c.control(parse_address("X3"), plc_cell::fatek::Action::Set);
    c.control(parse_address("M20"), plc_cell::fatek::Action::Disable);
    c.write(parse_address("R100"), {1234});
    c.write(parse_address("D5"), {5});
  }
  int port() const { return port_of(plc, "FATEK TCP"); }
  std::string target(const FatekProxy& p) const { return "fatek://" + loopback(p.port()); }
  std::string journal(const FatekProxy& p) const {
    std::string name = target(p);
    for (char& ch : name)
      if (!isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '.') ch = '_';
    return state_dir() + "/plc_cell/restore-" + name + ".journal";
  }
  std::vector<std::string> runner(const FatekProxy& p, std::vector<std::string> more = {}) const {
    std::vector<std::string> a = {PLC_CELL_TOOL, "test", kKill, "--target", target(p)};
    a.insert(a.end(), more.begin(), more.end());
    return a;
  }
  RunChild plc;
};

TEST_F(Killed, AtRandomRequestsOfACaseThePlcIsAsFoundEveryTime) {
  const PlcState before = state_of(port(), kPoints);
  FatekProxy proxy(port());
  const auto whole = test_tool({kKill, "--target", target(proxy)});
  ASSERT_EQ(whole.status, 0) << whole.out;
  const uint64_t total = proxy.requests();  // a whole run: measure, read, case, restore
  ASSERT_TRUE(state_of(port(), kPoints) == before) << describe(state_of(port(), kPoints), kPoints);
  std::mt19937 rng(41);
  const int signals[] = {SIGINT, SIGTERM, SIGKILL};
  int stopped = 0;  // runs a SIGINT or SIGTERM stopped
  for (int round = 0; round < 15; ++round) {
    const int sig = signals[round % 3];
    const uint64_t at = proxy.requests() + std::uniform_int_distribution<uint64_t>(1, total)(rng);
    ChildProcess run(runner(proxy));
    proxy.signal_at(at, run.pid(), sig);
    const int status = run.wait(std::chrono::seconds(60), "the runner's end after its signal");
    std::string where = "round " + std::to_string(round) + ", signal " + std::to_string(sig) + " at request " +
                        std::to_string(at) + " of " + std::to_string(total) + "\n" + run.output();
    if (sig == SIGKILL && proxy.fired()) {
      EXPECT_TRUE(WIFSIGNALED(status)) << where;
      struct stat st;
      const bool left = ::stat(journal(proxy).c_str(), &st) == 0;
      // The next run on the same PLC puts back what the killed one touched, then runs.
      const auto next = test_tool({kKill, "--target", target(proxy)});
      where += "\nthe next run:\n" + next.out;
      EXPECT_EQ(next.status, 0) << where;
      EXPECT_EQ(next.out.find("putting it back first") != std::string::npos, left) << where << "\n" << next.out;
    } else if (proxy.fired()) {
      // A signal at a request of the case stops it; one at a request of its restore (the
      // run's last requests: how many polls a case takes varies) finds nothing left to stop:
      // the run ends as a whole one, the PLC put back.
      const bool whole = WIFEXITED(status) && WEXITSTATUS(status) == 0 &&
                         run.output().find("== 1 passed, 0 failed") != std::string::npos &&
                         run.output().find("the PLC is as it was found") != std::string::npos;
      if (!whole) {
        ++stopped;
        EXPECT_EQ(WEXITSTATUS(status), 1) << where;
        EXPECT_NE(run.output().find(sig == SIGINT ? "stopped by SIGINT" : "stopped by SIGTERM"), std::string::npos)
            << where;
      }
      EXPECT_EQ(run.output().find("NOT RESTORED"), std::string::npos) << where;
    }
    const PlcState after = state_of(port(), kPoints);
    EXPECT_TRUE(after == before) << where << "\nfound: " << describe(before, kPoints)
                                 << "\nleft:  " << describe(after, kPoints);
  }
  // Of the ten SIGINT and SIGTERM rounds, most land in the case (its restore is a tenth of
  // a run's requests): a runner that let signals pass would stop none.
  std::printf("[ figures  ] %d of the 10 SIGINT and SIGTERM rounds stopped a case\n", stopped);
  EXPECT_GE(stopped, 5);
}

struct Fault {
  FatekProxy::Mode mode;
  const char* name;
  const char* says;  // in the case's failure
};

TEST_F(Killed, ALinkThatFailsMidCaseFailsItClearlyAndTheRestoreWaitsForTheLink) {
  const PlcState before = state_of(port(), kPoints);
  FatekProxy proxy(port());
  for (const Fault& f : {Fault{FatekProxy::Mode::Refuse, "a dropped connection", "connection closed"},
                         Fault{FatekProxy::Mode::Garble, "a garbled reply", "bad answer to command"},
                         Fault{FatekProxy::Mode::Late, "a device late by 600 ms", "within 200 ms"}}) {
    proxy.set_mode(FatekProxy::Mode::Forward);
    ChildProcess run(runner(proxy, {"--timeout", "200ms", "--retries", "1"}));
    // Past the measuring and the case's first reads: inside the case.
    proxy.mode_at(proxy.requests() + 60, f.mode, 600);
    ASSERT_TRUE(run.read_until("restore: the link is down", std::chrono::seconds(30))) << f.name << "\n"
                                                                                       << run.output();
    proxy.set_mode(FatekProxy::Mode::Forward);
    const int status = run.wait(std::chrono::seconds(60), "the runner's end once the link is back");
    const std::string& out = run.output();
    EXPECT_EQ(WEXITSTATUS(status), 1) << f.name << "\n" << out;
    EXPECT_NE(out.find("FAIL  " + kKill + ": forces and writes, then waits"), std::string::npos) << f.name << "\n"
                                                                                                 << out;
    const auto failure = out.find("the link to FATEK tcp " + loopback(proxy.port()) + " station 1 failed ");
    ASSERT_NE(failure, std::string::npos) << f.name << "\n" << out;
    EXPECT_NE(out.substr(failure, out.find('\n', failure) - failure).find(f.says), std::string::npos)
        << f.name << "\n" << out;
    EXPECT_NE(out.find("; the PLC is as it was found\n"), std::string::npos) << f.name << "\n" << out;
    const PlcState after = state_of(port(), kPoints);
    EXPECT_TRUE(after == before) << f.name << "\nfound: " << describe(before, kPoints)
                                 << "\nleft:  " << describe(after, kPoints);
  }
}

// A link that does not come back within --restore-timeout: what is not put back is named,
// point by point, and the next run puts it back first.
TEST_F(Killed, ALinkThatStaysDownLeavesEveryPointNamedAndTheNextRunPutsThemBack) {
  const PlcState before = state_of(port(), kPoints);
  FatekProxy proxy(port());
  proxy.mode_at(60, FatekProxy::Mode::Refuse);
  const auto r = test_tool({kKill, "--target", target(proxy), "--timeout", "200ms", "--restore-timeout", "1s"});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("    NOT RESTORED: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("NOT as it was found: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; the next run on " + target(proxy) + " puts them back first"), std::string::npos) << r.out;
  proxy.set_mode(FatekProxy::Mode::Forward);
  const auto next = test_tool({kKill, "--target", target(proxy)});
  EXPECT_EQ(next.status, 0) << next.out;
  EXPECT_NE(next.out.find("stopped before it put back what case 'forces and writes, then waits' touched"),
            std::string::npos)
      << next.out;
  EXPECT_TRUE(state_of(port(), kPoints) == before) << describe(state_of(port(), kPoints), kPoints);
}

}  // namespace
}  // namespace hardware_test
