// The scheduler calls a source's settle and advance_to only if its type has code for
// them (EventSource::steps_of), and the counters' unit does the same for its parts
// (Component::steps_of); a type that is not final is called for every step.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/hsc/hs_timer.h"
#include "plc_cell/hsc/hsc_counter.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/hsc/measured_input.h"
#include "plc_cell/hsc/terminal_edges.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace timeline {
namespace {

using Log = std::vector<std::string>;

// Acts at no instant of its own; logs each advance it is given, in ms.
class Advancing final : public EventSource {
 public:
  Advancing(std::string name, Log& log) : name_(std::move(name)), log_(log) {}
  uint64_t next_event_ns() override { return kNever; }
  void advance_to(uint64_t t) override { log_.push_back(name_ + " advance " + std::to_string(t / 1000000)); }
  void at(uint64_t) override {}

 private:
  std::string name_;
  Log& log_;
};

class Silent final : public EventSource {
 public:
  uint64_t next_event_ns() override { return kNever; }
  void at(uint64_t) override {}
};

class Open : public EventSource {  // not final: a derived class may add steps
 public:
  uint64_t next_event_ns() override { return kNever; }
  void at(uint64_t) override {}
};

static_assert(EventSource::steps_of<Advancing>() == EventSource::kAdvances, "one step declared");
static_assert(EventSource::steps_of<Silent>() == 0u, "no optional step");
static_assert(EventSource::steps_of<Open>() == EventSource::kEveryStep, "not final: every step");
// The units: the axes have nothing to settle or advance; the counters' unit has both.
static_assert(EventSource::steps_of<motion::MotionUnit>() == 0u, "the axes act at their instants only");
static_assert(EventSource::steps_of<hsc::HscUnit>() == EventSource::kEveryStep, "the counters' unit");
// The counters' parts.
static_assert(hsc::Component::steps_of<hsc::HscCounter>() == EventSource::kEveryStep, "a counter settles and advances");
static_assert(hsc::Component::steps_of<hsc::MeasuredInput>() == EventSource::kEveryStep, "so does a pulse measurement");
static_assert(hsc::Component::steps_of<hsc::TerminalEdges>() == 0u, "the edges act at instants only");
static_assert(hsc::Component::steps_of<hsc::TimeBaseInterrupt>() == 0u, "the time base acts at instants only");
static_assert(hsc::Component::steps_of<hsc::HstaTimer>() == 0u, "so does HSTA");

// advance_to reaches the sources that have it, in the order they were added, at every
// scan; a removed source is no longer advanced.
TEST(SourceSteps, AdvanceReachesTheSourcesThatHaveItInOrderUntilRemoved) {
  Plc plc;
  plc.load_program_text("ORG M1925\nOUT Y0\nEND\n", "test.il");
  Log log;
  Advancing a("a", log), b("b", log);
  Silent s;
  Scheduler* sched = plc.locked([&](ScanEngine& e, Memory&) {
    Scheduler& k = Scheduler::of(e);
    k.add_source(&a);
    k.add_source(&s);
    k.add_source(&b);
    return &k;
  });
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  for (int ms = 0; ms <= 2; ++ms) plc.scan(uint64_t(ms) * 1000);  // us
  EXPECT_EQ(log, (Log{"a advance 1", "b advance 1", "a advance 2", "b advance 2"}));
  log.clear();
  plc.locked([&](ScanEngine&, Memory&) {
    sched->remove_source(&a);
    return 0;
  });
  plc.scan(3000);
  EXPECT_EQ(log, (Log{"b advance 3"}));
  plc.locked([&](ScanEngine&, Memory&) {
    sched->remove_source(&b);
    sched->remove_source(&s);
    return 0;
  });
}

}  // namespace
}  // namespace timeline
}  // namespace plc_cell
