// The examples under examples/hsc/ as shipped: loaded through SoftCell (cell YAML +
// IL), run in virtual time, output timeline and counts checked.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/sim/soft_cell.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace hsc {
namespace {

constexpr uint64_t kMs = 1000000;  // ns

struct Change {
  uint64_t t_ns;
  uint32_t y;
  bool level;
};

class Example {
 public:
  explicit Example(const std::string& name)
      : cell(std::string(PLC_CELL_SOURCE_DIR) + "/examples/hsc/" + name + ".yaml", "") {
    cell.plc().locked([this](ScanEngine& e, Memory&) {
      cell.get<hsc::HscUnit>()->on_output([this](uint64_t t, uint32_t y, bool v) { outputs.push_back({t, y, v}); });
      timeline::Scheduler::of(e).on_isr([this](uint64_t t, int s) { isrs.push_back({t, s, cell.get<hsc::HscUnit>()->count(0),
                                                                        cell.get<hsc::HscUnit>()->count(1)}); });
      return 0;
    });
    EXPECT_TRUE(cell.plc().set_mode(RunMode::Run));
  }
  void run(uint64_t duration_us, uint64_t period_us = 1000) {
    for (uint64_t end = now_us + duration_us; now_us < end; now_us += period_us) cell.plc().scan(now_us);
  }
  std::vector<Change> of(uint32_t y) const {
    std::vector<Change> r;
    for (const auto& c : outputs)
      if (c.y == y) r.push_back(c);
    return r;
  }
  uint32_t get(const std::string& a) { return cell.plc().read(parse_address(a), 1).at(0); }

  struct Isr {
    uint64_t t_ns;
    int source;
    int64_t cv0, cv1;
  };
  SoftCell cell;
  std::vector<Change> outputs;
  std::vector<Isr> isrs;
  uint64_t now_us = 0;
};

TEST(ExampleFiles, Cutting) {
  Example e("cutting");
  e.run(2000000);
  ASSERT_EQ(e.isrs.size(), 4u);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(e.isrs[k].t_ns, (k + 1) * 250 * kMs);
    EXPECT_EQ(e.isrs[k].cv0, int64_t(1000 * (k + 1)));
  }
  const auto y1 = e.of(1);
  ASSERT_EQ(y1.size(), 8u);
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(y1[2 * k].t_ns, (k + 1) * 250 * kMs);
    EXPECT_EQ(y1[2 * k + 1].t_ns, (k + 1) * 250 * kMs + 100 * kMs);
  }
  EXPECT_EQ(e.get("DR4096"), 4400u);
}

TEST(ExampleFiles, CountUpStop) {
  Example e("count_up_stop");
  e.run(200000);
  const auto y0 = e.of(0);
  ASSERT_EQ(y0.size(), 2u);
  EXPECT_EQ(y0[1].t_ns, 54347827u);
  EXPECT_EQ(e.get("DR4096"), 100000u);
}

TEST(ExampleFiles, MultiZone) {
  Example e("multi_zone");
  e.run(2500000);
  // Zone ends 1000, 1500, 2500, 3000, 4200, 5000, 6000, 7000 counts at 4000 counts/s.
  const uint64_t ends_ms[8] = {250, 375, 625, 750, 1050, 1250, 1500, 1750};
  uint64_t start = 0;
  for (uint32_t z = 0; z < 8; ++z) {
    const auto c = e.of(8 + z);
    ASSERT_EQ(c.size(), 2u) << "Y" << 8 + z;
    EXPECT_EQ(c[0].t_ns, start) << "Y" << 8 + z;
    EXPECT_TRUE(c[0].level);
    EXPECT_EQ(c[1].t_ns, ends_ms[z] * kMs) << "Y" << 8 + z;
    start = ends_ms[z] * kMs;
  }
  const int64_t ends[8] = {1000, 1500, 2500, 3000, 4200, 5000, 6000, 7000};
  std::vector<Example::Isr> zone_isrs;
  for (const auto& i : e.isrs)
    if (i.source == kHsc0I + 1) zone_isrs.push_back(i);
  ASSERT_EQ(zone_isrs.size(), 8u);
  for (size_t k = 0; k < 8; ++k) {
    EXPECT_EQ(zone_isrs[k].cv1, ends[k]);
    EXPECT_EQ(zone_isrs[k].t_ns, ends_ms[k] * kMs);
  }
  // X3 at 2 s resets HSC1: 0.5 s later it holds 2000.
  EXPECT_EQ(e.get("DR4100"), 1996u);  // read by the scan at 2.499 s
  EXPECT_EQ(e.isrs.back().source, x_edge_source(3, false));
  EXPECT_EQ(e.isrs.back().t_ns, 2000 * kMs);
}

TEST(ExampleFiles, Rpm) {
  Example e("rpm");
  e.run(3000000);
  EXPECT_EQ(e.get("R100"), 1500u);
  EXPECT_EQ(e.get("DR4"), 4000u);
}

TEST(ExampleFiles, Drill) {
  Example e("drill");
  e.run(5000000, 2000);
  EXPECT_EQ(e.get("DR0"), 12u);
  EXPECT_EQ(e.get("M11"), 0u);
  EXPECT_EQ(e.isrs.size(), 999u);  // 5 ms .. 4.995 s (the last scan is at 4.998 s)
}

}  // namespace
}  // namespace hsc
}  // namespace plc_cell
