// The native engine's edge contacts and its calls of TMR, CTR, register RST and FUN
// (docs/native-engine.md): whole networks are machine code, and the memory equals the
// interpreter's after every scan and every interrupt routine.
#include <gtest/gtest.h>

#include <string>

#include "see3_function.h"
#include "two_engines.h"

using namespace plc_cell;

namespace {

// The differential fixture on this file's program text.
struct Engines : native_test::TwoEngines {
  explicit Engines(const std::string& text)
      : TwoEngines(native_test::see3_table(), text, "calls.il") {}
  std::string scan(uint32_t x, uint32_t dt, bool irq, int s) {
    set_inputs(static_cast<uint16_t>(x));
    return step(dt, irq, "scan " + std::to_string(s));
  }
};

// Every instruction kind that runs in a network, each edge contact form, counters of 16 and
// 32 bits, timers of two time bases, blocks nested into the stack array (level 4 and up:
// the first four levels are registers) and a three-input FUN.
const char* const kNetworks =
    "ORG TU X0\nAND TD X1\nLD TU X2\nOR TD X3\nANDLD\nLD NOT X4\nAND TU X5\nORLD\nOUT Y0\n"
    "ORG TD X6\nOR TU X7\nLD TD X8\nAND TU X9\nORLD\nCTR C1 5\nAND TU X10\nCTR C200 3\n"
    "ORG X11\nTMR T1 4\nORG X11\nTMR T60 2\nORG T1\nOUT Y1\nORG C1\nOUT Y2\n"
    "ORG X12\nRST C1\nAND X13\nRST T1\nORG TU X14\nRST D3\nOR X15\nRST R4\n"
    "ORG M1925\nINC.P R0\nAND X1\nADD.DP Sa=R2 Sb=7 D=R2\nORG X2\nMOV S=WX0 D=R6\n"
    "ORG X3\nLD X4\nLD TU X5\nLD X6\nLD TD X7\nLD X8\nAND X9\nORLD\nANDLD\nORLD\n"
    "SEE3.P D=R8\nOUT Y3\nORG X12\nLD X13\nLD TU X14\nSEE3 D=R9\nOUT Y4\n";

std::string program() {
  return std::string(kNetworks) + "END\nLBL X0+I\n" + kNetworks + "RTI\n";
}

}  // namespace

TEST(NativeEngine, WholeNetworksAreMachineCode) {
  Engines e(program());
  const native::NativeCode* nc = e.native.native_code();
  ASSERT_NE(nc, nullptr) << e.native.engine_status();
  // Two runs, the main program and the routine; END, LBL and RTI stay on the dispatch loop.
  ASSERT_EQ(nc->runs().size(), 2u) << e.native.engine_status();
  EXPECT_EQ(nc->native_instructions(), e.prog.code.size() - 3) << e.native.engine_status();
}

TEST(NativeEngine, EdgeContactsTimersCountersAndFunsEqualTheInterpreter) {
  Engines e(program());
  uint64_t r = 12345;
  auto next = [&r] { return static_cast<uint32_t>((r = r * 6364136223846793005ull + 1442695040888963407ull) >> 33); };
  for (int s = 1; s <= 4000; ++s) {
    const uint32_t x = next();
    const std::string d = e.scan(x, next() % 40000, next() % 5 == 0, s);
    ASSERT_EQ(d, "") << "scan " << s;
  }
  // The stimulus reached the interesting states: counters and timers done, FUNs ran.
  EXPECT_EQ(e.mem_n.bit(Area::Y, 2), e.mem_i.bit(Area::Y, 2));
  EXPECT_NE(e.mem_n.reg(Area::R, 8), 0u);
  EXPECT_NE(e.mem_n.reg(Area::R, 0), 0u);
}

TEST(NativeEngine, AForcedPointStopsTheCallsAsOnTheInterpreter) {
  Engines e("ORG X0\nTMR T2 1\nORG TU X1\nCTR C3 2\nORG T2\nOUT Y0\nORG C3\nOUT Y1\nEND\n");
  for (Memory* m : {&e.mem_i, &e.mem_n}) {
    m->set_disabled(Area::T, 2, true);
    m->set_disabled(Area::C, 3, true);
  }
  for (int s = 1; s <= 200; ++s) ASSERT_EQ(e.scan(s % 7 ? 3u : 0u, 20000, false, s), "") << s;
  EXPECT_FALSE(e.mem_n.bit(Area::Y, 0));  // the disabled T2 and C3 never turn on
  EXPECT_FALSE(e.mem_n.bit(Area::Y, 1));
  EXPECT_NE(e.mem_n.reg(Area::RC, 3), 0u);  // while the counter's value counts
}
