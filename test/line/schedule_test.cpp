// A line run cell by cell over windows of instants (Line::advance) is the same run as
// instant by instant (scan_at at each instant, the documented order: docs/lines.md, "One
// clock"): on random lines, from fixed seeds, every cell's values after every one of its
// scans are compared. The lines mix scan periods, wire kinds (exact inputs X0-X15, scanned
// inputs, relays and registers), delays (zero included), inversions, travelling parts and
// cycles of wires.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "line_fixture.h"

namespace plc_cell {
namespace testing {
namespace {

// Each cell counts the edges of its inputs, blinks Y0-Y15 on a timer of its own, and drives
// Y20 from two of its inputs and a relay, so a wire's value reaches the next cell's wires.
std::string program(int timer_k) {
  return "ORG X20\nFUN 15P INC D=R0\n"
         "ORG X0\nFUN 15P INC D=R1\n"
         "ORG X1\nFUN 15P INC D=R3\n"
         "ORG M10\nFUN 15P INC D=R4\n"
         "ORG NOT M1\nTMR T0 " + std::to_string(timer_k) + "\n"
         "ORG T0\nOUT M1\n"
         "ORG M1\nFUN 9 MOVN S=WY0 D=WY0\n"
         "ORG X21\nOR X1\nAND NOT M10\nOUT Y20\n"
         "ORG M1925\nFUN 8 MOV S=R0 D=R5\n"
         "END\n";
}

const char* const kBitSources[] = {"Y0", "Y3", "Y20"};
const char* const kWordSources[] = {"R0", "R1"};
const char* const kSinks[] = {"X0", "X1", "X20", "X21", "M10", "R10"};

struct RandomLine {
  std::map<std::string, std::string> files;
  size_t cells = 0;
};

RandomLine random_line(std::mt19937& rng) {
  const auto pick = [&](int n) { return int(rng() % uint32_t(n)); };
  RandomLine out;
  out.cells = size_t(2 + pick(5));
  const char* periods[] = {"0.001", "0.002", "0.003", "0.005"};
  std::string line = "cells:\n";
  for (size_t i = 0; i < out.cells; ++i) {
    const std::string c = "c" + std::to_string(i);
    out.files[c + ".il"] = program(1 + pick(6));
    out.files[c + ".yaml"] = cell_yaml(c, c + ".il", periods[pick(4)]);
    line += "  " + c + ": " + c + ".yaml\n";
  }
  line += "wires:\n";
  // Every cell is driven by one to three wires, each from another cell.
  for (size_t to = 0; to < out.cells; ++to) {
    std::vector<std::string> sinks(std::begin(kSinks), std::end(kSinks));
    std::shuffle(sinks.begin(), sinks.end(), rng);
    for (int k = 0, n = 1 + pick(3); k < n; ++k) {
      const size_t from = (to + 1 + size_t(pick(int(out.cells) - 1))) % out.cells;
      const std::string& sink = sinks[size_t(k)];
      const bool word = sink[0] == 'R';
      const std::string source = word ? kWordSources[pick(2)] : kBitSources[pick(3)];
      std::string wire = "{from: c" + std::to_string(from) + "." + source + ", to: c" + std::to_string(to) + "." + sink;
      const int kind = word ? pick(2) : pick(4);
      if (kind == 1) wire += ", delay: " + std::to_string(pick(4) * 1500) + "us";
      if (kind == 2) wire += ", delay: " + std::to_string(pick(3)) + "ms, invert: true";
      if (kind == 3) wire += ", part: {travel: " + std::to_string(1 + pick(20)) + "ms, length: " + std::to_string(1 + pick(9)) + "ms}";
      line += "  - " + wire + "}\n";
    }
  }
  out.files["l.line.yaml"] = line;
  return out;
}

// Every cell's values after each of its scans, in that cell's order.
using Runs = std::vector<std::vector<std::vector<uint32_t>>>;

const char* const kWatched[] = {"X0", "X1", "X20", "X21", "M10", "M1", "Y0", "Y20", "R0", "R1", "R3", "R4", "R5", "R10"};

Runs run(const std::string& path, bool windows, std::mt19937& chunks, uint64_t until_us) {
  line::Line l(path);
  Runs out(l.size());
  std::vector<std::vector<Address>> watched(l.size());
  for (size_t i = 0; i < l.size(); ++i)
    for (const char* a : kWatched) watched[i].push_back(l.cell(i)->config().resolve(a));
  l.after_scan([&](size_t i, uint64_t t) {
    std::vector<uint32_t> v{uint32_t(t)};
    l.cell(i)->plc().locked([&](ScanEngine&, Memory& m) {
      for (const Address& a : watched[i]) v.push_back(m.read(a));
      return 0;
    });
    out[i].push_back(std::move(v));
  }, line::Line::Observer::PerCell);
  l.run();
  const uint64_t tick = l.tick_us();
  for (uint64_t t = 0; t < until_us;) {
    if (!windows) {
      l.scan_at(t);
      t += tick;
      continue;
    }
    const uint64_t next = std::min(until_us, t + tick * (1 + chunks() % 700));  // windows cut anywhere
    l.advance(t, next);
    t = next;
  }
  return out;
}

TEST(Schedule, WindowsCellByCellGiveTheSameScansAsInstantByInstant) {
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const RandomLine rl = random_line(rng);
    LineFolder f("schedule_" + std::to_string(seed), rl.files);
    std::mt19937 chunks(seed * 7919);
    const uint64_t until = 1200000;  // 1.2 s: the timers' blinks and the parts come and go
    const Runs a = run(f.path("l.line.yaml"), false, chunks, until);
    const Runs b = run(f.path("l.line.yaml"), true, chunks, until);
    ASSERT_EQ(a.size(), b.size());
    for (size_t c = 0; c < a.size(); ++c) {
      ASSERT_EQ(a[c].size(), b[c].size()) << "seed " << seed << " cell c" << c << "\n" << rl.files.at("l.line.yaml");
      for (size_t s = 0; s < a[c].size(); ++s)
        ASSERT_EQ(a[c][s], b[c][s]) << "seed " << seed << " cell c" << c << " scan " << s << " at " << a[c][s][0]
                                    << " us\n" << rl.files.at("l.line.yaml");
    }
  }
}

TEST(Schedule, TheRandomLinesCarrySomething) {
  // The comparison above means something only if the wires move values: over the seeds, a
  // good share of the sinks' counters count.
  size_t counted = 0, cells = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937 rng(seed);
    const RandomLine rl = random_line(rng);
    LineFolder f("schedule_carry_" + std::to_string(seed), rl.files);
    std::mt19937 chunks(seed);
    const Runs a = run(f.path("l.line.yaml"), true, chunks, 1200000);
    for (const auto& scans : a) {
      ++cells;
      const std::vector<uint32_t>& last = scans.back();
      counted += last[9] + last[10] + last[11] + last[12] > 0;  // R0, R1, R3, R4: edges seen
    }
  }
  EXPECT_GT(counted * 3, cells) << counted << " of " << cells << " cells counted an edge of a wire";
}

TEST(Schedule, AWholeLineObserverRunsInstantByInstant) {
  // An observer that reads every cell at each instant (Observer::Line) sees them all at
  // the instant it is called for, as scan_at gives it.
  LineFolder f("schedule_observer", {{"p.il", program(3)}, {"a.yaml", cell_yaml("a", "p.il")},
                                     {"b.yaml", cell_yaml("b", "p.il")},
                                     {"l.line.yaml", "cells: {a: a.yaml, b: b.yaml}\nwires:\n  - {from: a.Y0, to: b.X20, delay: 5ms}\n"}});
  line::Line l(f.path("l.line.yaml"));
  std::vector<uint64_t> last(2, 0);
  bool apart = false;
  l.after_scan([&](size_t i, uint64_t t) {
    last[i] = t;
    if (i == 1 && last[0] != t) apart = true;  // b's scan at t after a's at t
  });
  l.run();
  l.advance(0, 500000);
  EXPECT_FALSE(apart);
  EXPECT_EQ(last[0], 499000u);
  EXPECT_EQ(last[1], 499000u);
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
