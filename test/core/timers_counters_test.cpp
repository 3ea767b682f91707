// Timers and counters against hand-computed timelines in virtual time.
//
// Rule (docs/program-format.md): a timer starts counting at the scan that first sees
// its input on and adds the time between scans in units of its base, so with scan
// period P its contact turns on at the first scan k with k * P >= PV * base.
#include "plc_fixture.h"

using namespace plc_cell;

class TimersCounters : public BothEnginesFixture {};
PLC_CELL_ON_BOTH_ENGINES(TimersCounters);

TEST_P(TimersCounters, TimerBasesFollowTheTimerNumber) {
  // T0-T49: 0.01 s, T50-T199: 0.1 s, T200-T255: 1 s (FBs default).
  load("ORG X0\nTMR T0 100\nORG X0\nTMR T50 10\nORG X0\nTMR T200 1\nEND\n");
  input(0, true);
  scans(1);  // t = 0: timers start, current value 0
  EXPECT_EQ(get("RT0"), 0u);
  scans(999);  // last scan at t = 0.999 s
  EXPECT_EQ(get("T0"), 0u);
  EXPECT_EQ(get("RT0"), 99u);
  EXPECT_EQ(get("RT50"), 9u);
  EXPECT_EQ(get("RT200"), 0u);
  scans(1);  // t = 1.000 s
  EXPECT_EQ(get("T0"), 1u);
  EXPECT_EQ(get("T50"), 1u);
  EXPECT_EQ(get("T200"), 1u);
  EXPECT_EQ(get("RT0"), 100u);
  scans(500);  // the value stays at the preset
  EXPECT_EQ(get("RT0"), 100u);
}

TEST_P(TimersCounters, TimerResetsWhenItsInputDrops) {
  load("ORG X0\nTMR T60 5\nORG T60\nOUT Y0\nEND\n");
  input(0, true);
  scans(300);  // 0.3 s: RT60 = 2 (at t=0.299 s it has 299 ms -> 2 ticks)
  EXPECT_EQ(get("RT60"), 2u);
  input(0, false);
  scans(1);
  EXPECT_EQ(get("RT60"), 0u);
  EXPECT_EQ(get("T60"), 0u);
  input(0, true);
  scans(500);  // t = 0.499 s after restart -> still off
  EXPECT_EQ(get("Y0"), 0u);
  scans(1);
  EXPECT_EQ(get("T60"), 1u);
  EXPECT_EQ(get("Y0"), 1u);  // the contact is read later in the same scan
}

TEST_P(TimersCounters, ScanPeriodsThatDoNotDivideTheBaseCarryTheRemainder) {
  // 0.01 s base, 3 ms scans: 20 ticks = 200 ms -> on at the first k with 3k >= 200, k = 67.
  load("ORG X0\nTMR T1 20\nEND\n");
  input(0, true);
  scans(67, 3000);
  EXPECT_EQ(get("T1"), 0u);  // k = 66 at the last scan: 198 ms
  scans(1, 3000);
  EXPECT_EQ(get("T1"), 1u);
}

TEST_P(TimersCounters, PresetFromARegister) {
  load("ORG X0\nTMR T2 R100\nEND\n");
  put("R100", 5);  // 5 x 0.01 s
  input(0, true);
  scans(50);
  EXPECT_EQ(get("T2"), 0u);
  scans(1);
  EXPECT_EQ(get("T2"), 1u);
}

TEST_P(TimersCounters, RstClearsATimer) {
  load("ORG X0\nTMR T3 1000\nORG X1\nRST T3\nEND\n");
  input(0, true);
  scans(100);
  EXPECT_EQ(get("RT3"), 9u);
  input(1, true);
  scans(1);
  EXPECT_EQ(get("RT3"), 0u);
}

TEST_P(TimersCounters, CounterCountsRisingEdgesUpToThePreset) {
  load("ORG X0\nCTR C0 3\nORG C0\nOUT Y0\nORG X1\nRST C0\nEND\n");
  for (int pulse = 1; pulse <= 5; ++pulse) {
    input(0, true);
    scans(2);
    input(0, false);
    scans(2);
    EXPECT_EQ(get("RC0"), uint32_t(std::min(pulse, 3))) << pulse;
  }
  EXPECT_EQ(get("C0"), 1u);
  EXPECT_EQ(get("Y0"), 1u);
  input(1, true);
  scans(1);
  EXPECT_EQ(get("RC0"), 0u);
  EXPECT_EQ(get("C0"), 0u);
}

TEST_P(TimersCounters, ThirtyTwoBitCounter) {
  load("ORG X0\nCTR C200 100000\nEND\n");
  plc.write(parse_address("DRC200"), {99998});
  for (int i = 0; i < 3; ++i) {
    input(0, true);
    scans(1);
    input(0, false);
    scans(1);
  }
  EXPECT_EQ(plc.read(parse_address("DRC200"), 1)[0], 100000u);
  EXPECT_EQ(get("C200"), 1u);
}

TEST_P(TimersCounters, CounterValuesSurviveStopRunOnlyWhenRetentive) {
  plc.locked([](ScanEngine& e, Memory&) {
    e.set_retentive({{Area::RC, 5, 5}});
    return 0;
  });
  load("ORG X0\nCTR C4 10\nORG X0\nCTR C5 10\nEND\n");
  input(0, true);
  scans(1);
  input(0, false);
  scans(1);
  EXPECT_EQ(get("RC4"), 1u);
  EXPECT_EQ(get("RC5"), 1u);
  plc.set_mode(RunMode::Stop);
  plc.set_mode(RunMode::Run);
  EXPECT_EQ(get("RC4"), 0u);
  EXPECT_EQ(get("RC5"), 1u);
}
