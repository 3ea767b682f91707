// The engine calls a hook only in the scan phases its type has code for
// (ScanHook::phases_of), and every phase of a hook added through a type that is not final.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/motion/motion_unit.h"
#include "plc_cell/sim/simulated_cell.h"
#include "plc_cell/temp/rtc.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace {

using Log = std::vector<std::string>;

class AfterOnly final : public ScanHook {
 public:
  explicit AfterOnly(Log& log) : log_(log) {}
  void after_program(uint64_t) override { log_.push_back("after"); }

 private:
  Log& log_;
};

// Not final: a class derived from it may add phases, so all are called.
class Base : public ScanHook {
 public:
  explicit Base(Log& log) : log_(log) {}
  void before_inputs(uint64_t) override { log_.push_back("base inputs"); }

 protected:
  Log& log_;
};

class Derived final : public Base {
 public:
  using Base::Base;
  void before_program(uint64_t) override { log_.push_back("derived program"); }
};

static_assert(ScanHook::phases_of<AfterOnly>() == ScanHook::kAfterProgram, "one phase declared");
static_assert(ScanHook::phases_of<Base>() == ScanHook::kEveryPhase, "not final: every phase");
static_assert(ScanHook::phases_of<Derived>() == (ScanHook::kBeforeInputs | ScanHook::kBeforeProgram),
              "an inherited override counts");
static_assert(ScanHook::phases_of<ScanHook>() == ScanHook::kEveryPhase, "the base itself: every phase");

// The units: what each declares is what the engine calls.
static_assert(ScanHook::phases_of<timeline::Scheduler>() == ScanHook::kBeforeInputs, "the clock before the inputs");
static_assert(ScanHook::phases_of<SimulatedCell>() == ScanHook::kBeforeInputs, "the terminals");
static_assert(ScanHook::phases_of<motion::MotionUnit>() == (ScanHook::kBeforeProgram | ScanHook::kAfterProgram),
              "the axes' status around the program");
static_assert(ScanHook::phases_of<temp::Rtc>() == (ScanHook::kBeforeInputs | ScanHook::kBeforeProgram), "the RTC");
static_assert(ScanHook::phases_of<hsc::HscUnit>() == ScanHook::kEveryPhase, "the counters in every phase");

// A PLC in RUN with the hooks added; scans at 1 ms, 2 ms, ...
class Hooked {
 public:
  Hooked() {
    plc_.load_program_text("ORG M0\nOUT Y0\nEND\n", "phases.il");
    EXPECT_TRUE(plc_.set_mode(RunMode::Run));
  }
  template <class T>
  void add(T* h) {
    plc_.locked([h](ScanEngine& e, Memory&) {
      e.add_hook(h);
      return 0;
    });
  }
  void remove(ScanHook* h) {
    plc_.locked([h](ScanEngine& e, Memory&) {
      e.remove_hook(h);
      return 0;
    });
  }
  void scan() { plc_.scan(now_us_ += 1000); }
  Plc& plc() { return plc_; }

 private:
  Plc plc_;
  uint64_t now_us_ = 0;
};

TEST(ScanHookPhases, AHookIsCalledInTheOnePhaseItDeclares) {
  Hooked h;
  Log log;
  AfterOnly hook(log);
  h.add(&hook);
  h.scan();
  h.scan();
  EXPECT_EQ(log, (Log{"after", "after"}));
}

TEST(ScanHookPhases, AHookAddedThroughANonFinalBaseIsCalledInEveryPhaseItOverrides) {
  Hooked h;
  Log log;
  Derived hook(log);
  h.add(static_cast<Base*>(&hook));
  h.scan();
  EXPECT_EQ(log, (Log{"base inputs", "derived program"}));
}

TEST(ScanHookPhases, PhasesKeepTheOrderHooksWereAddedInAndARemovedHookLeavesThemAll) {
  Hooked h;
  Log log;
  AfterOnly first(log);
  Derived second(log);
  AfterOnly third(log);
  h.add(&first);
  h.add(&second);
  h.add(&third);
  h.scan();
  EXPECT_EQ(log, (Log{"base inputs", "derived program", "after", "after"}));
  log.clear();
  h.remove(&second);
  h.remove(&first);
  h.scan();
  EXPECT_EQ(log, (Log{"after"}));
  log.clear();
  h.remove(&third);
  h.scan();
  EXPECT_TRUE(log.empty());
}

TEST(ScanHookPhases, OnlyTheInputPhaseRunsInStop) {
  Hooked h;
  Log log;
  Derived hook(log);
  h.add(&hook);
  h.plc().set_mode(RunMode::Stop);
  h.scan();
  EXPECT_EQ(log, (Log{"base inputs"}));
}

}  // namespace
}  // namespace plc_cell
