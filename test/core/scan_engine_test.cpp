#include "plc_fixture.h"

#include "plc_cell/core/error.h"

using namespace plc_cell;

using ScanEngineTest = PlcFixture;

TEST_F(ScanEngineTest, FirstScanPulseAndAlwaysOn) {
  load("ORG M1924\nINC R0\nORG M1925\nINC R1\nEND\n");
  scans(10);
  EXPECT_EQ(get("R0"), 1u);
  EXPECT_EQ(get("R1"), 10u);
  plc.set_mode(RunMode::Stop);
  plc.set_mode(RunMode::Run);  // no retentive ranges here: R0 is cleared, the pulse comes again
  scans(1);
  EXPECT_EQ(get("R0"), 1u);
}

TEST_F(ScanEngineTest, ClockPulsesHaveTheirPeriods) {
  // Count rising edges of M1920 (10 ms) and M1921 (100 ms) over one second.
  load("ORG TU M1920\nINC R0\nORG TU M1921\nINC R1\nORG TU M1922\nINC R2\nEND\n");
  scans(1000);  // t = 0 .. 0.999 s
  EXPECT_EQ(get("R0"), 100u);
  EXPECT_EQ(get("R1"), 10u);
  EXPECT_EQ(get("R2"), 1u);
}

TEST_F(ScanEngineTest, TheMinuteClockIsOnForTheSecondHalfOfEachMinute) {
  load("ORG TU M1923\nINC R0\nORG TD M1923\nINC R1\nEND\n");
  scans(29999, 1000);  // t = 0 .. 29.998 s: off
  EXPECT_EQ(get("R0"), 0u);
  scans(1, 1000);  // t = 29.999 s
  EXPECT_EQ(get("M1923"), 0u);
  scans(1, 1000);  // t = 30 s
  EXPECT_EQ(get("M1923"), 1u);
  EXPECT_EQ(get("R0"), 1u);
  // Scan periods that are no divisor of 5 ms land anywhere in the half periods.
  now_us = 59999999;
  scans(1, 7);
  EXPECT_EQ(get("M1923"), 1u);
  scans(1, 7);  // 60.000006 s
  EXPECT_EQ(get("M1923"), 0u);
  EXPECT_EQ(get("R1"), 1u);
  EXPECT_EQ(get("M1920"), 0u);  // 60.000006 s is in an even 5 ms half period: 10 ms clock off
  now_us = 60005000;
  scans(1);
  EXPECT_EQ(get("M1920"), 1u);
  EXPECT_EQ(get("M1921"), 0u);
  now_us = 60050000;  // the 100 ms clock's second half
  scans(1);
  EXPECT_EQ(get("M1921"), 1u);
}

TEST_F(ScanEngineTest, AForcedSpecialRelayKeepsItsStateAndItsNeighboursAreTheirOwn) {
  load("ORG M1922\nOUT Y0\nORG M1925\nOUT Y1\nORG M1926\nOUT Y2\nEND\n");
  plc.force(parse_address("M1925"), ForceAction::Disable);
  plc.force(parse_address("M1925"), ForceAction::Reset);
  plc.force(parse_address("M1922"), ForceAction::Disable);
  plc.force(parse_address("M1922"), ForceAction::Set);
  put("M1926", 1);
  put("M1927", 1);
  scans(3);  // t = 0 .. 2 ms: the 1 s clock is off, M1925 is always on
  EXPECT_EQ(get("M1922"), 1u);
  EXPECT_EQ(get("Y0"), 1u);
  EXPECT_EQ(get("M1925"), 0u);
  EXPECT_EQ(get("Y1"), 0u);
  EXPECT_EQ(get("M1926"), 1u);
  EXPECT_EQ(get("M1927"), 1u);
  EXPECT_EQ(get("Y2"), 1u);
  plc.force(parse_address("M1925"), ForceAction::Enable);
  plc.force(parse_address("M1922"), ForceAction::Enable);
  scans(1);
  EXPECT_EQ(get("M1925"), 1u);
  EXPECT_EQ(get("M1922"), 0u);
  put("M1920", 1);  // a client's write between scans is overwritten at the next
  put("M1924", 1);
  scans(1);
  EXPECT_EQ(get("M1920"), 0u);
  EXPECT_EQ(get("M1924"), 0u);
}

TEST_F(ScanEngineTest, InputImageIsTakenOncePerScan) {
  load("ORG X0\nOUT Y0\nEND\n");
  input(0, true);
  EXPECT_EQ(get("X0"), 0u);  // not before the next scan
  scans(1);
  EXPECT_EQ(get("X0"), 1u);
  EXPECT_EQ(get("Y0"), 1u);
}

TEST_F(ScanEngineTest, DisabledInputIgnoresTheTerminal) {
  load("ORG X0\nOUT Y0\nEND\n");
  plc.force(parse_address("X0"), ForceAction::Disable);
  plc.force(parse_address("X0"), ForceAction::Set);
  scans(1);
  EXPECT_EQ(get("Y0"), 1u);
  input(0, false);  // the wire says off; the disabled point stays on
  scans(2);
  EXPECT_EQ(get("Y0"), 1u);
  plc.force(parse_address("X0"), ForceAction::Enable);
  input(0, false);
  scans(1);
  EXPECT_EQ(get("Y0"), 0u);
}

TEST_F(ScanEngineTest, StopTurnsOutputsOffAndFreezesTheProgram) {
  load("ORG M1925\nOUT Y0\nINC R0\nEND\n");
  scans(5);
  EXPECT_EQ(plc.set_mode(RunMode::Stop), true);
  EXPECT_EQ(get("Y0"), 0u);
  scans(5);
  EXPECT_EQ(get("R0"), 5u);  // frozen in STOP (cleared only on STOP -> RUN)
  put("R0", 42);
  scans(3);
  EXPECT_EQ(get("R0"), 42u);
}

TEST_F(ScanEngineTest, RunWithoutProgramIsRefused) {
  Plc empty;
  EXPECT_FALSE(empty.set_mode(RunMode::Run));
  EXPECT_EQ(empty.mode(), RunMode::Stop);
}

TEST_F(ScanEngineTest, AFailedLoadKeepsTheRunningProgram) {
  load("ORG X0\nOUT Y0\nEND\n");
  EXPECT_THROW(plc.load_program_text("ORG X0\nOUT Y999\nEND\n", "bad.il"), SourceError);
  input(0, true);
  scans(1);
  EXPECT_EQ(get("Y0"), 1u);
  EXPECT_EQ(plc.mode(), RunMode::Run);
}

TEST_F(ScanEngineTest, WritesAreAllOrNothing) {
  load("END\n");
  put("R8070", 1);
  EXPECT_THROW(plc.write(parse_address("R8070"), {5, 6, 7}), Error);
  EXPECT_EQ(get("R8070"), 1u);
  EXPECT_THROW(plc.write(parse_address("R0"), {1, 70000}), Error);
  EXPECT_EQ(get("R0"), 0u);
  EXPECT_THROW(plc.write(parse_address("X0"), {2}), Error);
  EXPECT_THROW(plc.write(parse_address("R0"), {}), Error);
  EXPECT_THROW(plc.force(parse_address("R0"), ForceAction::Set), Error);
}

TEST_F(ScanEngineTest, WritingAnInputPlaysTheSensor) {
  load("ORG X3\nOUT Y3\nEND\n");
  put("X3", 1);
  scans(3);  // the terminal keeps the written level across input refreshes
  EXPECT_EQ(get("Y3"), 1u);
  plc.write(parse_address("WX0"), {0});
  scans(1);
  EXPECT_EQ(get("Y3"), 0u);
}

TEST_F(ScanEngineTest, WatchdogStopsASlowScan) {
  load("ORG M1925\nOUT Y0\nEND\n");
  plc.locked([](ScanEngine& e, Memory&) {
    e.set_watchdog_us(1000);
    e.report_cycle(500000, 0, 0);  // 0.5 ms: fine
    return 0;
  });
  EXPECT_EQ(plc.mode(), RunMode::Run);
  const bool tripped = plc.locked([](ScanEngine& e, Memory&) {
    e.report_cycle(1500000, 20000, 1);
    return e.watchdog_tripped();
  });
  EXPECT_TRUE(tripped);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  const ScanStats st = plc.locked([](ScanEngine& e, Memory&) { return e.stats(); });
  EXPECT_EQ(st.cycle.count, 2u);
  EXPECT_EQ(st.cycle.max_ns, 1500000u);
  EXPECT_EQ(st.cycle.min_ns, 500000u);
  EXPECT_DOUBLE_EQ(st.cycle.avg_ns(), 1000000.0);
  EXPECT_EQ(st.overruns, 1u);
  EXPECT_EQ(st.wake_latency.max_ns, 20000u);
}

TEST_F(ScanEngineTest, SameInputsSameResultEveryRun) {
  auto run_once = [] {
    Plc p;
    p.load_program_text("ORG M1921\nTMR T10 3\nORG T10\nINC R0\nORG TU M1922\nCTR C1 100\nEND\n", "d.il");
    p.set_mode(RunMode::Run);
    for (uint64_t t = 0; t < 5000000; t += 700) p.scan(t);
    return p.read(parse_address("R0"), 4);
  };
  const auto a = run_once();
  EXPECT_EQ(a, run_once());
  EXPECT_GT(a[0], 0u);
}
