// FUN148 MPG: a handwheel (an analytic encoder counted by HSC0) drives an axis
// from the 50 ms time-base interrupt: the manual's example E (register snapshot,
// x1/x10/x100), the remainder of Fa/Fb, R4020 travel limits, resource management.
#include <fstream>
#include <sstream>

#include <yaml-cpp/yaml.h>

#include "motion_fixture.h"
#include "plc_cell/motion/mpg.h"

namespace plc_cell {
namespace motion {
namespace {

std::string example_il() {
  std::ifstream f(std::string(PLC_CELL_SOURCE_DIR) + "/examples/motion/mpg.il");
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// HSC0 in A/B x1 (MD4) on X0/X1, turned by the handwheel encoder "wheel".
hsc::HscConfig wheel_counter() {
  return hsc::parse_hsc_config(
      YAML::Load("hsc0: {mode: MD4}\nsources:\n  - {name: wheel, type: encoder, a: X0, hz: 0}\n"), "cell.yaml");
}

struct MpgCell : MotionCell {
  explicit MpgCell(const std::string& il = example_il()) : MotionCell(il, true, wheel_counter()) {
    AxisParams p;  // the manual's example: P4 = 200 kHz, P8 = 30 ms
    p.p4_max = 200000;
    p.p8_acc_ms = 30;
    params(p, 2000);
    params(p, 2100);
    run(100000, kScan);
  }
  static constexpr uint64_t kScan = 10000;  // 10 ms scans; the 50MSI runs between them
  // Turns the wheel at hz (periods per second, negative = backwards) for ms, then stops
  // it and lets the MPG take its last samples and finish its output.
  void turn(double hz, uint64_t ms) {
    run(1000, 1000);  // a scan now: the rate then changes at this instant, ms before the stop
    plc.locked([&](ScanEngine&, Memory&) { counters->set_source_rate("wheel", hz); });
    run(ms * 1000, 1000);  // 1 ms scans: the rate changes at a scan's instant
    plc.locked([&](ScanEngine&, Memory&) { counters->set_source_rate("wheel", 0); });
    run(200000, kScan);
  }
  int64_t cv() {
    return plc.locked([&](ScanEngine&, Memory&) { return counters->count(0); });
  }
  void select(int x, bool on) { plc.set_input(x, on); }
};

TEST(Fun148, ManualExampleE_RegisterSnapshot) {
  MpgCell c;
  c.select(36, true);  // x100
  // Both MPGs disabled: the counter moves, no axis does, and the MPGs follow the count.
  c.turn(1000, 10351);
  ASSERT_EQ(c.cv(), 10351);
  EXPECT_EQ(c.get32("DR4088"), 0);
  EXPECT_EQ(c.get32("DR4090"), 0);
  // Example 2's axis: X33 -> Ps1, 210 input pulses x 100 / 1.
  c.select(33, true);
  c.turn(1000, 210);
  EXPECT_EQ(c.get32("DR4090"), 21000);
  c.select(33, false);
  // Example 1's axis: X32 -> Ps0, 1142 input pulses x 100.
  c.select(32, true);
  c.turn(1000, 1142);
  // The manual's snapshot of example 1.
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get32("DR4082"), 0);
  EXPECT_EQ(c.get32("DR4088"), 114200);
  EXPECT_EQ(c.get32("DR4090"), 21000);
  EXPECT_EQ(c.cv(), 11703);
  EXPECT_EQ(c.get("D800"), 0u);        // 2 x Ps (inferred)
  EXPECT_EQ(c.get("D801"), 0x0100u);   // EN on, Ps0
  EXPECT_EQ(c.get32("DD802"), 11703);  // the counter at the last sample
  EXPECT_EQ(c.get("D810"), 2u);
  EXPECT_EQ(c.get("D811"), 0x0001u);   // EN off, Ps1
  EXPECT_EQ(c.get32("DD812"), 11703);  // a disabled MPG still follows the counter
  EXPECT_EQ(c.get("M500"), 0u);        // ACT: nothing to send now
  // Example 2's snapshot: X33 instead of X32.
  c.select(32, false);
  c.select(33, true);
  c.run(100000, MpgCell::kScan);
  EXPECT_EQ(c.get("D801"), 0x0000u);
  EXPECT_EQ(c.get("D811"), 0x0101u);
  EXPECT_EQ(c.get32("DR4090"), 21000);  // enabling sends nothing old
}

TEST(Fun148, MultipliersAndBothDirectionsAreExact) {
  MpgCell c;
  c.select(32, true);
  const struct {
    int x;
    int mult;
    double hz;
    uint64_t ms;
  } turns[] = {{34, 1, 1000, 37}, {35, 10, 1000, 123}, {36, 100, 400, 250}, {35, 10, -1000, 55}, {34, 1, -500, 10}};
  int64_t expect = 0;
  for (const auto& t : turns) {
    for (int x = 34; x <= 36; ++x) c.select(x, x == t.x);
    c.run(20000, MpgCell::kScan);
    const int64_t before = c.cv();
    c.turn(t.hz, t.ms);
    const int64_t in = c.cv() - before;
    EXPECT_EQ(in, static_cast<int64_t>(t.hz * t.ms / 1000));  // the wheel's own count
    expect += in * t.mult;                                   // output = input x Fa / Fb
    EXPECT_EQ(c.get32("DR4088"), expect) << "x" << t.mult << " at " << t.hz << " Hz";
  }
  EXPECT_EQ(expect, 37 + 1230 + 10000 - 550 - 5);
  // While the wheel turns the axis follows one 50 ms sample behind: 400 Hz x 100 =
  // 2000 pulses per sample, each sent within its interval (P8 = 30 ms ramps at 200 kHz).
  c.select(36, true);
  c.select(34, false);
  c.run(20000, MpgCell::kScan);
  const int64_t cv0 = c.cv();
  c.plc.locked([&](ScanEngine&, Memory&) { c.counters->set_source_rate("wheel", 400); });
  bool act = false;
  for (int k = 0; k < 50; ++k) {
    c.run(10000, MpgCell::kScan);
    act = act || c.get("M500") == 1;
  }
  EXPECT_TRUE(act);  // ACT while sending
  // At most two samples (2 x 20 input pulses) behind the wheel.
  const int64_t target = expect + (c.cv() - cv0) * 100;
  EXPECT_LE(c.get32("DR4088"), target);
  EXPECT_GE(c.get32("DR4088"), target - 2 * 2000);
}

TEST(Fun148, TheRemainderOfFaOverFbIsKept) {
  MpgCell c;
  c.put("D700", 1);
  c.put("D701", 3);  // x 1/3
  c.select(32, true);
  int64_t in = 0;
  for (int k = 0; k < 10; ++k) {  // 7 pulses per sample: each alone would send 2 (6 of 7)
    const int64_t before = c.cv();
    c.turn(140, 50);
    in += c.cv() - before;
  }
  ASSERT_EQ(in, 70);
  EXPECT_EQ(c.get32("DR4088"), 23);  // 70 / 3 = 23 rem 1, not 10 x 2 = 20
  const int64_t before = c.cv();
  c.turn(1000, 2);                   // 2 more: 72 / 3 = 24 exactly
  ASSERT_EQ(c.cv() - before, 2);
  EXPECT_EQ(c.get32("DR4088"), 24);
}

TEST(Fun148, R4020LimitsBlockOneDirection) {
  MpgCell c;
  c.put("D700", 1);
  c.select(32, true);
  c.put("R4020", 0x5501);  // 55H: limits active; b0: no forward movement of Ps0
  c.turn(1000, 100);
  EXPECT_EQ(c.get32("DR4088"), 0);
  c.turn(-1000, 30);  // backward is allowed
  EXPECT_EQ(c.get32("DR4088"), -30);
  c.put("R4020", 0x5502);  // b1: no backward movement of Ps0
  c.turn(-1000, 30);
  EXPECT_EQ(c.get32("DR4088"), -30);
  c.turn(1000, 50);
  EXPECT_EQ(c.get32("DR4088"), 20);
  c.put("R4020", 0x0003);  // high byte not 55H: no limits
  c.turn(1000, 10);
  c.turn(-1000, 5);
  EXPECT_EQ(c.get32("DR4088"), 25);
}

// FUN142 PSOFF stops an MPG output on its axis and drops the input not yet sent.
TEST(Fun148, PsoffStopsTheOutput) {
  std::string il = example_il();
  il.replace(il.find("END"), 3, "ORG M5\nPSOFF.P N=0\nEND");
  MpgCell c(il);
  c.put("D700", 100);
  c.select(32, true);
  c.put("M100", 1);
  // 50 wheel periods x100 = 5000 pulses at 200 kHz with 30 ms ramps: about 55 ms of output.
  c.run(1000, 1000);
  c.plc.locked([&](ScanEngine&, Memory&) { c.counters->set_source_rate("wheel", 1000); });
  c.run(50000, 1000);
  c.plc.locked([&](ScanEngine&, Memory&) { c.counters->set_source_rate("wheel", 0); });
  c.run(10000, 1000);  // the next 50 ms sample has started the output
  ASSERT_EQ(c.get("M500"), 1u);
  c.put("M5", 1);
  c.run(1000, 1000);
  const int32_t stopped = c.get32("DR4088");
  EXPECT_GT(stopped, 0);
  EXPECT_LT(stopped, 5000);
  EXPECT_EQ(c.get32("DR4080"), 0);
  EXPECT_EQ(c.get32("DR4072"), 5000 - stopped);
  c.run(300000, 1000);
  EXPECT_EQ(c.get32("DR4088"), stopped);  // nothing more, the rest is dropped
  EXPECT_EQ(c.get("M1992"), 1u);
}

TEST(Fun148, RefusedWhileAnotherInstructionHoldsTheAxis) {
  std::string il = example_il();
  il.replace(il.find("END"), 3, "ORG M1\nLD M2\nLD M3\nHSPSO Ps=0 SR=R0 WR=R100 ACT=M10 ERR=M11 DN=M12\nEND");
  MpgCell c(il);
  c.table("SPD 1000\nDRV ADR,+,1000,Ps\nGOTO NEXT\nMEND\n");
  c.put("D700", 1);
  c.select(32, true);
  c.put("M1", 1);  // FUN140 holds Ps0 for about 1 s
  c.run(20000, MpgCell::kScan);
  EXPECT_EQ(c.get("M1992"), 0u);
  c.turn(1000, 300);  // the wheel turns while FUN140 sends: the MPG sends nothing
  EXPECT_EQ(c.get("M500"), 0u);
  ASSERT_TRUE(c.run_until([&] { return c.get("M1996") == 1; }, 5000000, MpgCell::kScan));
  EXPECT_EQ(c.get32("DR4088"), 1000);  // FUN140's stroke only
  c.put("M1", 0);
  c.turn(1000, 40);  // free again: the MPG moves it
  EXPECT_EQ(c.get32("DR4088"), 1040);
  EXPECT_EQ(c.get("M1992"), 1u);  // released once its output ended
}

}  // namespace
}  // namespace motion
}  // namespace plc_cell
