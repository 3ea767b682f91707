// The TRi FMD1616 quadrature decodings of an A/B counter (TRi manual §7.1-7.3):
// simple, enhanced (anti-jiggle), x1, x2, x4, on hand-made transitions, on
// scheduled edges and on an analytic encoder, and their configuration errors.
//
// Expected values come from the manual's text:
//  §7.1 "if Phase A leads Phase B the HSC increments on every pulse ... lags ...
//       decrements. If Phase B is OFF, pulses arriving at Phase A ... incremented.
//       If Phase A is OFF, pulses arriving at Phase B will decrement."
//  §7.2 the simple method gives "multiple counts if the rotor shaft jiggles at the
//       transition edge of the phase"; enhanced "will lock out multiple counting by
//       examining the co-relationship between the two phases".
//  §7.3 "by 1 for each full cycle"; x2 "by 1 for every two transition edges"; x4
//       "every transition edge".
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <vector>

#include "hsc_fixture.h"
#include "plc_cell/core/error.h"
#include "plc_cell/hsc/decoding.h"
#include "plc_cell/hsc/hsc_config.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

Pins P(bool a, bool b) { return Pins{a, b}; }

const Decoding kAll[] = {Decoding::Simple, Decoding::Enhanced, Decoding::X1, Decoding::X2, Decoding::X4};

// Net count of a level sequence, from a fresh decoder (as at RUN).
int run(Decoding d, const std::vector<Pins>& seq) {
  DecodeState s;
  int cv = 0;
  for (size_t i = 1; i < seq.size(); ++i) cv += decode_delta(Mode::AB, d, &s, seq[i - 1], seq[i]);
  return cv;
}

std::vector<Pins> cycles(int n, bool forward) {
  // Forward: A leads B by a quarter cycle; backward: B leads A.
  const std::vector<Pins> fwd = {P(1, 0), P(1, 1), P(0, 1), P(0, 0)};
  const std::vector<Pins> back = {P(0, 1), P(1, 1), P(1, 0), P(0, 0)};
  std::vector<Pins> seq = {P(0, 0)};
  for (int k = 0; k < n; ++k)
    for (const Pins& p : forward ? fwd : back) seq.push_back(p);
  return seq;
}

TEST(TriDecoding, CleanRunsCountOncePerCycleTwiceInX2FourTimesInX4) {
  // 5 full quadrature cycles: simple, enhanced and x1 count 5, x2 10, x4 20; backwards negative.
  const int per_cycle[] = {1, 1, 1, 2, 4};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(run(kAll[i], cycles(5, true)), 5 * per_cycle[i]) << decoding_name(kAll[i]);
    EXPECT_EQ(run(kAll[i], cycles(5, false)), -5 * per_cycle[i]) << decoding_name(kAll[i]);
  }
}

TEST(TriDecoding, SimpleCountsSinglePhasePulsesOnAQuadraturePair) {
  // B OFF: 4 pulses on A count up 4. A OFF: 3 pulses on B count down 3.
  std::vector<Pins> on_a = {P(0, 0)}, on_b = {P(0, 0)};
  for (int k = 0; k < 4; ++k) on_a.insert(on_a.end(), {P(1, 0), P(0, 0)});
  for (int k = 0; k < 3; ++k) on_b.insert(on_b.end(), {P(0, 1), P(0, 0)});
  EXPECT_EQ(run(Decoding::Simple, on_a), 4);
  EXPECT_EQ(run(Decoding::Simple, on_b), -3);
  // A true quadrature decoder sees a phase going back and forth, not a movement:
  // single-phase counting is what the manual names as simple's advantage (§7.2).
  EXPECT_EQ(run(Decoding::X1, on_a), 0);
  EXPECT_EQ(run(Decoding::X4, on_a), 0);
  EXPECT_EQ(run(Decoding::Enhanced, on_a), 1);   // only the first pulse: the rest are jiggles
  EXPECT_EQ(run(Decoding::Enhanced, on_b), -1);
}

TEST(TriDecoding, JigglingOnAPhaseEdgeCountsInSimpleAndX1NotInEnhanced) {
  // One clean forward cycle brings the encoder to its A edge with B OFF; there A
  // jiggles: up, down, up, down, up (3 rising edges), ending a quarter past the edge.
  std::vector<Pins> seq = cycles(1, true);
  seq.insert(seq.end(), {P(1, 0), P(0, 0), P(1, 0), P(0, 0), P(1, 0)});
  // The shaft moved one cycle and one quarter across the counting edge: 2 counts.
  EXPECT_EQ(run(Decoding::Enhanced, seq), 2);
  // Simple counts every A pulse with B OFF: each jiggle is one more count.
  EXPECT_EQ(run(Decoding::Simple, seq), 4);
  // x1 follows the edge back and forth: the net count is right, but CV moves on
  // every jiggle edge.
  EXPECT_EQ(run(Decoding::X1, seq), 2);
  // x2 and x4 follow it too: 2 and 4 for the cycle, 1 for the final quarter.
  EXPECT_EQ(run(Decoding::X2, seq), 3);
  EXPECT_EQ(run(Decoding::X4, seq), 5);
  DecodeState s1, se;
  std::vector<int> x1_steps, enhanced_steps;
  for (size_t i = 1; i < seq.size(); ++i) {
    x1_steps.push_back(decode_delta(Mode::AB, Decoding::X1, &s1, seq[i - 1], seq[i]));
    enhanced_steps.push_back(decode_delta(Mode::AB, Decoding::Enhanced, &se, seq[i - 1], seq[i]));
  }
  EXPECT_EQ(x1_steps, (std::vector<int>{1, 0, 0, 0, 1, -1, 1, -1, 1}));
  EXPECT_EQ(enhanced_steps, (std::vector<int>{1, 0, 0, 0, 1, 0, 0, 0, 0}));
}

TEST(TriDecoding, JigglingOnTheBEdgeWithAOffCountsDownInSimpleOnly) {
  // One cycle backwards to the B edge with A OFF, then B jiggles: up, down, up,
  // down, up (3 rising edges), ending a quarter past the edge.
  std::vector<Pins> seq = cycles(1, false);
  seq.insert(seq.end(), {P(0, 1), P(0, 0), P(0, 1), P(0, 0), P(0, 1)});
  // One cycle and one crossing of the counting edge backwards: -2.
  EXPECT_EQ(run(Decoding::Enhanced, seq), -2);
  EXPECT_EQ(run(Decoding::Simple, seq), -4);  // each B pulse with A OFF counts down
  // x1 counts at an edge of A (MD4): the cycle's, not B's jiggle.
  EXPECT_EQ(run(Decoding::X1, seq), -1);
}

TEST(TriDecoding, ReversalsCountBackExactlyInEnhanced) {
  // Forward through "both OFF" (+1), back through it (-1), forward again (+1).
  const std::vector<Pins> seq = {P(0, 1), P(0, 0), P(1, 0), P(0, 0), P(0, 1), P(0, 0), P(1, 0)};
  EXPECT_EQ(run(Decoding::Enhanced, seq), 1);
  // A step changing both phases is illegal: it counts nothing in any decoding.
  for (Decoding d : kAll) {
    DecodeState s;
    EXPECT_EQ(decode_delta(Mode::AB, d, &s, P(0, 0), P(1, 1)), 0) << decoding_name(d);
  }
}

TEST(TriDecoding, X1X2X4AreTheFatekMultipliers) {
  // Every transition of two levels: x1, x2, x4 count as MD4, MD5, MD7.
  const struct {
    Decoding d;
    Mode m;
  } pairs[] = {{Decoding::X1, Mode::AB}, {Decoding::X2, Mode::ABx2}, {Decoding::X4, Mode::ABx4}};
  for (const auto& pr : pairs)
    for (int from = 0; from < 4; ++from)
      for (int to = 0; to < 4; ++to) {
        DecodeState s;
        const Pins a = P(from & 1, from & 2), b = P(to & 1, to & 2);
        EXPECT_EQ(decode_delta(Mode::AB, pr.d, &s, a, b), count_delta(pr.m, a, b)) << decoding_name(pr.d);
      }
}

// ---- on the counters: scheduled edges ---------------------------------------

const char* kIdle = "ORG M1925\nOUT M0\nEND\n";

// HSC0 (A = X0, B = X1) with PV in DR4098 and an HSC0I routine: the ISR log shows
// every instant at which counting makes CV equal PV.
std::string with_pv(int32_t pv) {
  return "ORG M1924\nFUN 8D MOV S=" + std::to_string(pv) +
         " D=DR4098\nFUN 93 HSCTW CN=0 D=1\nORG M1925\nOUT M0\nEND\n"
         "LBL HSC0I\nORG M1925\nFUN 15 INC D=R0\nRTI\n";
}

void schedule(HscCell& cell, const std::vector<Pins>& seq, uint64_t step_ns) {
  cell.with([&](HscUnit& u) {
    for (size_t i = 1; i < seq.size(); ++i) {
      u.schedule_edge(0, i * step_ns, seq[i].a);
      u.schedule_edge(1, i * step_ns, seq[i].b);
    }
    return 0;
  });
}

TEST(TriDecodingCounters, JiggleOnScheduledEdges) {
  // The jiggle above on X0/X1, one step per ms; PV = 2, reached when the shaft
  // first crosses the counting edge after the clean cycle (step 5, at 5 ms).
  std::vector<Pins> seq = cycles(1, true);
  seq.insert(seq.end(), {P(1, 0), P(0, 0), P(1, 0), P(0, 0), P(1, 0)});
  struct Want {
    const char* decoding;
    int64_t cv;
    std::vector<uint64_t> matches;
  };
  const Want wants[] = {
      {"enhanced", 2, {5 * kMs}},                   // the jiggle is locked out
      {"simple", 4, {5 * kMs}},                     // passes PV, then counts each jiggle
      {"x1", 2, {5 * kMs, 7 * kMs, 9 * kMs}},       // back and forth: PV again on each jiggle
      {"x2", 3, {3 * kMs, 6 * kMs, 8 * kMs}},       // both A edges: 2 after the cycle's A falling
      {"x4", 5, {2 * kMs}},                         // every edge: 2 at the second, never back to 2
  };
  for (const Want& w : wants) {
    HscCell cell(std::string("counters:\n  hsc0: {mode: MD4, decoding: ") + w.decoding + "}\n", with_pv(2));
    schedule(cell, seq, kMs);
    cell.run(12000, 1000);
    EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), w.cv) << w.decoding;
    std::vector<uint64_t> at;
    for (const auto& r : cell.runs_of(kHsc0I)) at.push_back(r.t_ns);
    EXPECT_EQ(at, w.matches) << w.decoding;
  }
}

TEST(TriDecodingCounters, CleanRunsFromCountersEdgesInTheYaml) {
  // Three cycles forward, or three backward, one step per ms, as `counters.edges`
  // of the cell YAML: 3 counts per direction in simple, enhanced, x1; 6 in x2; 12 in x4.
  const int per_cycle[] = {1, 1, 1, 2, 4};
  for (bool forward : {true, false}) {
    const std::vector<Pins> seq = cycles(3, forward);
    std::string xa = "    - {x: X0, steps: [", xb = "    - {x: X1, steps: [";
    for (size_t i = 1; i < seq.size(); ++i) {
      const std::string t = "[" + std::to_string(i) + "ms, ";
      xa += (i > 1 ? ", " : "") + t + (seq[i].a ? "1" : "0") + "]";
      xb += (i > 1 ? ", " : "") + t + (seq[i].b ? "1" : "0") + "]";
    }
    for (int i = 0; i < 5; ++i) {
      HscCell cell(std::string("counters:\n  hsc0: {mode: MD4, decoding: ") + decoding_name(kAll[i]) +
                       "}\n  edges:\n" + xa + "]}\n" + xb + "]}\n",
                   kIdle);
      cell.run(14000, 1000);  // 12 steps at 1 ... 12 ms
      EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), (forward ? 3 : -3) * per_cycle[i])
          << decoding_name(kAll[i]) << (forward ? " forward" : " backward");
    }
  }
}

TEST(TriDecoding, EnhancedCountsAReversalOnceItHasPassedBackThroughBothOff) {
  // Two cycles forward end with both phases OFF, entered by B falling. Going back,
  // simple counts at once (B rises with A OFF); enhanced counts once the encoder has
  // gone back through the whole "both OFF" quarter, a cycle later. Per cycle both count 1.
  std::vector<Pins> seq = cycles(2, true);
  const std::vector<Pins> back = cycles(2, false);
  seq.insert(seq.end(), back.begin() + 1, back.end());
  EXPECT_EQ(run(Decoding::Simple, std::vector<Pins>(seq.begin(), seq.begin() + 9)), 2);
  EXPECT_EQ(run(Decoding::Enhanced, std::vector<Pins>(seq.begin(), seq.begin() + 9)), 2);
  EXPECT_EQ(run(Decoding::Simple, std::vector<Pins>(seq.begin(), seq.begin() + 10)), 1);    // B rose with A OFF
  EXPECT_EQ(run(Decoding::Enhanced, std::vector<Pins>(seq.begin(), seq.begin() + 10)), 2);  // back out the way it came
  EXPECT_EQ(run(Decoding::Simple, std::vector<Pins>(seq.begin(), seq.begin() + 14)), 0);
  EXPECT_EQ(run(Decoding::Enhanced, std::vector<Pins>(seq.begin(), seq.begin() + 14)), 1);  // through "both OFF": -1
  EXPECT_EQ(run(Decoding::Simple, seq), 0);
  EXPECT_EQ(run(Decoding::Enhanced, seq), 1);
}

TEST(TriDecodingCounters, SimpleCountsSinglePhasePulsesOnScheduledEdges) {
  // HSC4, a software counter in MD4 on X4/X5: 6 pulses on A with B OFF (up 6),
  // then 2 pulses on B with A OFF (down 2).
  HscCell cell("counters:\n  hsc4: {mode: MD4, a: X4, b: X5, decoding: simple}\n", kIdle);
  cell.with([](HscUnit& u) {
    for (int k = 0; k < 6; ++k) {
      u.schedule_edge(4, (1 + k) * kMs, true);
      u.schedule_edge(4, (1 + k) * kMs + kMs / 2, false);
    }
    for (int k = 0; k < 2; ++k) {
      u.schedule_edge(5, (10 + k) * kMs, true);
      u.schedule_edge(5, (10 + k) * kMs + kMs / 2, false);
    }
    return 0;
  });
  cell.run(8000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 6);
  cell.run(6000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(4); }), 4);
  EXPECT_EQ(cell.get("DR4112"), 4u);
}

TEST(TriDecodingCounters, SimpleCountsAPulseGeneratorOnAWithBOff) {
  // An analytic single-phase generator (1 kHz) on A, nothing on B: 1 count per pulse.
  HscCell cell("counters:\n  hsc0: {mode: MD4, decoding: simple}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n",
               kIdle);
  cell.run(100000, 1000);
  cell.run(1, 1);  // a scan at exactly 100 ms
  // Rising edges at 0 (RUN sees A already ON: not an edge), 1 ms, ..., 100 ms: 100.
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 100);
  // Enhanced: the generator's first edge is A falling (A is ON at RUN); from then on
  // every A rising edge leaves "both OFF" by the phase it entered by: a jiggle, 0.
  HscCell enh("counters:\n  hsc0: {mode: MD4, decoding: enhanced}\n  sources:\n    - {name: gen, a: X0, hz: 1000}\n",
              kIdle);
  enh.run(100000, 1000);
  EXPECT_EQ(enh.with([](HscUnit& u) { return u.count(0); }), 0);
}

TEST(TriDecodingCounters, EnhancedFollowsThePhasesWhileMasked) {
  // MASK (X2) stops the count, not the decoder: a pulse on A while masked leaves it
  // knowing A changed last, so the next A rising edge is a jiggle (0); a clean cycle
  // after it counts 1.
  HscCell cell("counters:\n  hsc0: {mode: MD4, mask: true, decoding: enhanced}\n", kIdle);
  cell.with([](HscUnit& u) {
    u.schedule_edge(2, 1 * kMs, true);  // masked from 1 to 4 ms
    u.schedule_edge(0, 2 * kMs, true);
    u.schedule_edge(0, 3 * kMs, false);
    u.schedule_edge(2, 4 * kMs, false);
    u.schedule_edge(0, 5 * kMs, true);   // A rises with B OFF, as it did at 2 ms: no count
    u.schedule_edge(1, 6 * kMs, true);   // then the encoder turns forward one cycle
    u.schedule_edge(0, 7 * kMs, false);
    u.schedule_edge(1, 8 * kMs, false);
    u.schedule_edge(0, 9 * kMs, true);   // through "both OFF": +1
    return 0;
  });
  cell.run(6000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 0);
  cell.run(5000, 1000);
  EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), 1);
}

// ---- on the counters: an analytic encoder, CV=PV at the exact ns --------------

// A 3 Hz encoder on X0/X1 (one quarter cycle = 1/12 s, not a whole number of ns).
// The source's position is exact: quarter q is reached at ceil(q / 12 s) in ns.
// At RUN it is at the start of its first quarter: A ON, B OFF.
std::string encoder(const char* decoding) {
  return std::string("counters:\n  hsc0: {mode: MD4, decoding: ") + decoding +
         "}\n  sources:\n    - {name: enc, type: encoder, a: X0, hz: 3}\n";
}

TEST(TriDecodingCounters, AnalyticEncoderHitsPvAtTheExactNs) {
  // A rises with B OFF at quarters 4, 8, ...: simple, enhanced and x1 reach PV = 2
  // at quarter 8 = 2/3 s -> 666666667 ns. x2 counts both A edges (quarters 2, 4, 6):
  // PV = 3 at quarter 6 = 0.5 s. x4 counts every quarter: PV = 5 at 5/12 s -> 416666667 ns.
  const struct {
    const char* d;
    int pv;
    uint64_t t;
  } cases[] = {{"simple", 2, 666666667},
               {"enhanced", 2, 666666667},
               {"x1", 2, 666666667},
               {"x2", 3, 500000000},
               {"x4", 5, 416666667}};
  for (const auto& c : cases) {
    HscCell cell(encoder(c.d), with_pv(c.pv));
    cell.run(1600000, 800000);  // scans at 0 and 0.8 s: the instant is solved at RUN, 5 to 8 boundaries ahead
    const auto runs = cell.runs_of(kHsc0I);
    ASSERT_EQ(runs.size(), 1u) << c.d;
    EXPECT_EQ(runs[0].t_ns, c.t) << c.d;
    EXPECT_EQ(runs[0].cv[0], c.pv) << c.d;
  }
}

TEST(TriDecodingCounters, AnalyticEncoderReversingInsideBothOff) {
  // Forward to 300 ms (position 0.9 cycle: quarter 3, both phases OFF, entered by
  // B falling), then backwards at 3 Hz. Quarter 2 again at 350000001 ns (position
  // below 0.75 cycle), quarter -1 at 600000001 ns (below 0), quarter -2 at
  // 683333334 ns (below -0.25 cycle). PV = -1:
  //  * simple: B rises with A OFF at 350000001 ns: -1 (it counts the way back at once);
  //  * enhanced: leaving "both OFF" through B, the phase it came in by, is no movement
  //    across the counting edge; it counts -1 only after passing through "both OFF"
  //    backwards, at quarter -2: 683333334 ns;
  //  * x1, x2, x4: A falls with B OFF at quarter -1: 600000001 ns (x2 and x4 at -1 there too:
  //    x2 counted +1 at quarter 2 forward, -1 at quarter 1 and -1 at quarter -1;
  //    x4 counts the position in quarters).
  const struct {
    const char* d;
    uint64_t t;
  } cases[] = {{"simple", 350000001}, {"enhanced", 683333334}, {"x1", 600000001}, {"x2", 600000001}, {"x4", 600000001}};
  for (const auto& c : cases) {
    HscCell cell(encoder(c.d), with_pv(-1));
    cell.run(600000, 300000);  // scans at 0 and 300 ms
    cell.with([](HscUnit& u) {
      u.set_source_rate("enc", -3.0);
      return 0;
    });
    // The next scan at 1.2 s: each instant is solved at 300 ms, enhanced's at the
    // fifth boundary back, past the one its memory locks out.
    cell.now_us = 1200000;
    cell.run(1, 1);
    const auto runs = cell.runs_of(kHsc0I);
    ASSERT_GE(runs.size(), 1u) << c.d;
    EXPECT_EQ(runs[0].t_ns, c.t) << c.d;
    EXPECT_EQ(runs[0].cv[0], -1) << c.d;
  }
}

TEST(TriDecodingCounters, EnhancedCountsLongAnalyticSpansExactly) {
  // The reversal above, read at 1.2 s: position 0.9 - 0.9 * 3 = -1.8 cycles, quarter -8.
  // Backwards from quarter 3 the boundaries 3>2 ... -7>-8 are crossed (11, in one
  // span from the scan at 300 ms to the scan at 1.2 s). Counts on the way back:
  //  enhanced: through "both OFF" backwards at -1>-2 and -5>-6: -2;
  //  simple: B rising with A OFF at 3>2, -1>-2, -5>-6: -3;
  //  x1: A falling with B OFF at 0>-1 and -4>-5: -2.
  const struct {
    const char* d;
    int64_t cv;
  } cases[] = {{"enhanced", -2}, {"simple", -3}, {"x1", -2}};
  for (const auto& c : cases) {
    HscCell cell(encoder(c.d), kIdle);
    cell.run(301000, 1000);
    cell.with([](HscUnit& u) {
      u.set_source_rate("enc", -3.0);
      return 0;
    });
    cell.now_us = 1200000;  // the next scan is at 1.2 s: one span of 11 boundaries
    cell.run(1, 1);
    EXPECT_EQ(cell.with([](HscUnit& u) { return u.count(0); }), c.cv) << c.d;
  }
}

// ---- configuration --------------------------------------------------------------

HscConfig parse(const std::string& text) { return parse_hsc_config(YAML::Load(text)["counters"], "cell.yaml"); }

std::string error_of(const std::string& text) {
  try {
    parse(text);
  } catch (const SourceError& e) {
    return e.diagnostics().at(0).to_string();
  }
  return "";
}

TEST(TriDecodingConfig, DefaultIsTheFatekModeAndEachNameIsAccepted) {
  const HscConfig plain = parse("counters:\n  hsc0: {mode: MD4}\n  hsc1: {mode: MD7}\n");
  EXPECT_EQ(plain.counters[0].decoding, Decoding::Fatek);
  EXPECT_EQ(plain.counters[1].decoding, Decoding::Fatek);
  for (Decoding d : kAll) {
    const HscConfig c =
        parse(std::string("counters:\n  hsc4: {mode: MD4, a: X4, b: X5, decoding: ") + decoding_name(d) + "}\n");
    EXPECT_EQ(c.counters[4].decoding, d) << decoding_name(d);
    EXPECT_EQ(c.counters[4].mode, Mode::AB);
  }
}

TEST(TriDecodingConfig, ErrorsNameTheLineAndTheReason) {
  EXPECT_EQ(error_of("counters:\n  hsc0: {mode: MD4, decoding: x3}\n"),
            "cell.yaml:2:31: error: key 'counters.hsc0.decoding': 'x3': expected simple, enhanced, x1, x2 or x4");
  EXPECT_EQ(error_of("counters:\n  hsc0:\n    mode: MD0\n    decoding: simple\n"),
            "cell.yaml:4:15: error: key 'counters.hsc0.decoding': decoding is for an A/B counter (mode: MD4); "
            "MD0 counts U/D pulses");
  EXPECT_EQ(error_of("counters:\n  hsc3: {mode: MD2, decoding: enhanced}\n"),
            "cell.yaml:2:31: error: key 'counters.hsc3.decoding': decoding is for an A/B counter (mode: MD4); "
            "MD2 counts P/R pulses");
  EXPECT_EQ(error_of("counters:\n  hsc0: {mode: MD7, decoding: x4}\n"),
            "cell.yaml:2:31: error: key 'counters.hsc0.decoding': MD7 has its own multiplier; use mode: MD4 "
            "with decoding: x4");
  EXPECT_EQ(error_of("counters:\n  hsc1: {type: timer, decoding: simple}\n"),
            "cell.yaml:2:33: error: key 'counters.hsc1.decoding': a high-speed timer takes no further items");
  EXPECT_NE(error_of("counters:\n  hsc0: {mode: MD4, decoding: [x1]}\n").find("counters.hsc0.decoding"),
            std::string::npos);
  EXPECT_NE(error_of("counters:\n  hsc0: {mode: MD4, decoding: Simple}\n").find("'Simple': expected simple"),
            std::string::npos);
}

TEST(TriDecodingConfig, ARejectedConfigChangesNothing) {
  HscConfig cfg = parse("counters:\n  hsc0: {mode: MD4, decoding: enhanced}\n");
  EXPECT_THROW(cfg = parse("counters:\n  hsc0: {mode: MD4, decoding: fast}\n"), SourceError);
  EXPECT_TRUE(cfg.counters[0].used);
  EXPECT_EQ(cfg.counters[0].decoding, Decoding::Enhanced);
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
