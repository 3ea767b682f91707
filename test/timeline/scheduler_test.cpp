// The cell's scheduler: one clock for every subsystem with events between scans, and the
// interrupt requests of one instant dispatched together by priority (manual §9.3).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {
namespace timeline {
namespace {

constexpr uint64_t kUs = 1000;

// A source whose instants are given: it logs what it is asked and raises `request` when it acts.
class Scripted : public EventSource {
 public:
  Scripted(std::string name, std::vector<uint64_t> instants, std::vector<std::string>* log, int request = -1)
      : name_(std::move(name)), instants_(std::move(instants)), log_(log), request_(request) {}
  void bind(Scheduler* s) { sched_ = s; }
  void start(uint64_t t) override { log_->push_back(name_ + " start " + std::to_string(t)); }
  uint64_t next_event_ns() override { return next_ < instants_.size() ? instants_[next_] : kNever; }
  void advance_to(uint64_t t) override {
    if (next_event_ns() == t) log_->push_back(name_ + " advance " + std::to_string(t));
  }
  void at(uint64_t t) override {
    if (next_event_ns() != t) return;
    log_->push_back(name_ + " at " + std::to_string(t) + " clock " + std::to_string(sched_->now_ns()));
    ++next_;
    if (request_ >= 0) sched_->raise(request_);
  }

 private:
  std::string name_;
  std::vector<uint64_t> instants_;
  std::vector<std::string>* log_;
  int request_;
  size_t next_ = 0;
  Scheduler* sched_ = nullptr;
};

// Two routines that take a ticket (R0 + 1) into R11 (HSC0I) and R12 (X0+I).
constexpr const char* kProgram = R"(ORG M1924
FUN 8 MOV S=0 D=R20
END
LBL HSC0I
ORG M1925
FUN 15 INC D=R0
FUN 8 MOV S=R0 D=R11
RTI
LBL X0+I
ORG M1925
FUN 15 INC D=R0
FUN 8 MOV S=R0 D=R12
RTI
)";

struct Cell {
  Plc plc;
  Scheduler* sched = nullptr;
  std::vector<std::pair<uint64_t, int>> isrs;
  Cell() {
    plc.load_program_text(kProgram, "test.il");
    sched = plc.locked([](ScanEngine& e, Memory&) { return &Scheduler::of(e); });
    sched->on_isr([this](uint64_t t, int s) { isrs.push_back({t, s}); });
  }
  void add(Scripted* s) {
    s->bind(sched);
    plc.locked([&](ScanEngine&, Memory&) {
      sched->add_source(s);
      return 0;
    });
  }
  void run_ms(int ms) {
    for (int i = 0; i <= ms; ++i) plc.scan(uint64_t(i) * 1000);
  }
  uint32_t get(const std::string& a) { return plc.read(parse_address(a), 1).at(0); }
};

TEST(Scheduler, OnePerEngineMadeOnFirstUse) {
  Plc plc;
  EXPECT_EQ(plc.locked([](ScanEngine& e, Memory&) { return Scheduler::find(&e); }), nullptr);
  Scheduler* a = plc.locked([](ScanEngine& e, Memory&) { return &Scheduler::of(e); });
  Scheduler* b = plc.locked([](ScanEngine& e, Memory&) { return &Scheduler::of(e); });
  EXPECT_EQ(a, b);
  EXPECT_EQ(plc.locked([](ScanEngine& e, Memory&) { return Scheduler::find(&e); }), a);
}

TEST(Scheduler, VisitsEveryInstantOfEverySourceInTimeOrder) {
  Cell c;
  std::vector<std::string> log;
  Scripted a("a", {1500 * kUs, 3200 * kUs}, &log), b("b", {700 * kUs, 3200 * kUs}, &log);
  c.add(&a);
  c.add(&b);
  ASSERT_TRUE(c.plc.set_mode(RunMode::Run));
  c.run_ms(5);
  // RUN starts every source at the first scan's instant; at a shared instant every source
  // is brought there before any acts, and they act in the order they were added.
  const std::vector<std::string> want = {
      "a start 0",          "b start 0",         "b advance 700000",  "b at 700000 clock 700000",
      "a advance 1500000",  "a at 1500000 clock 1500000", "a advance 3200000", "b advance 3200000",
      "a at 3200000 clock 3200000", "b at 3200000 clock 3200000"};
  EXPECT_EQ(log, want);
}

TEST(Scheduler, RequestsOfOneInstantRunByPriorityNotByWhoActedFirst) {
  Cell c;
  std::vector<std::string> log;
  // a acts first and requests X0+I (priority 18); b, at the same instant, HSC0I (priority 10).
  Scripted a("a", {1500 * kUs}, &log, irq::x_edge_source(0, false)), b("b", {1500 * kUs}, &log, irq::kHsc0I);
  c.add(&a);
  c.add(&b);
  ASSERT_TRUE(c.plc.set_mode(RunMode::Run));
  c.run_ms(3);
  ASSERT_EQ(c.isrs.size(), 2u);
  EXPECT_EQ(c.isrs[0], std::make_pair(uint64_t(1500 * kUs), int(irq::kHsc0I)));
  EXPECT_EQ(c.isrs[1], std::make_pair(uint64_t(1500 * kUs), irq::x_edge_source(0, false)));
  EXPECT_EQ(c.get("R11"), 1u);
  EXPECT_EQ(c.get("R12"), 2u);
}

TEST(Scheduler, ASourceAddedDuringRunStartsAtThePresentInstant) {
  Cell c;
  std::vector<std::string> log;
  ASSERT_TRUE(c.plc.set_mode(RunMode::Run));
  c.run_ms(2);
  Scripted late("late", {2500 * kUs}, &log, irq::kHsc0I);
  c.add(&late);
  for (int i = 3; i <= 4; ++i) c.plc.scan(uint64_t(i) * 1000);
  EXPECT_EQ(log, (std::vector<std::string>{"late start 2000000", "late advance 2500000",
                                           "late at 2500000 clock 2500000"}));
  ASSERT_EQ(c.isrs.size(), 1u);
  EXPECT_EQ(c.isrs[0].first, 2500 * kUs);
  c.plc.locked([&](ScanEngine&, Memory&) {
    c.sched->remove_source(&late);
    return 0;
  });
}

// Most scans fall between events and end at once; an instant that falls on a scan's own
// instant, or a request made between scans, must still be served in that scan.
TEST(Scheduler, AnInstantOnAScanActsInThatScan) {
  Cell c;
  std::vector<std::string> log;
  Scripted a("a", {2000 * kUs, 4000 * kUs}, &log, irq::kHsc0I);
  c.add(&a);
  ASSERT_TRUE(c.plc.set_mode(RunMode::Run));
  c.run_ms(2);
  EXPECT_EQ(log, (std::vector<std::string>{"a start 0", "a advance 2000000", "a at 2000000 clock 2000000"}));
  ASSERT_EQ(c.isrs.size(), 1u);
  EXPECT_EQ(c.isrs[0].first, 2000 * kUs);
  EXPECT_EQ(c.get("R11"), 1u);  // the routine ran before the scan's program
  c.plc.scan(3000);
  EXPECT_EQ(log.size(), 3u);
  c.plc.scan(4000);
  EXPECT_EQ(log.back(), "a at 4000000 clock 4000000");
  EXPECT_EQ(c.get("R11"), 2u);
}

TEST(Scheduler, StopsMovingTheClockInStop) {
  Cell c;
  std::vector<std::string> log;
  Scripted a("a", {1500 * kUs}, &log);
  c.add(&a);
  c.run_ms(3);  // never set to RUN
  EXPECT_TRUE(log.empty());
  EXPECT_FALSE(c.sched->running());
}

}  // namespace
}  // namespace timeline
}  // namespace plc_cell
