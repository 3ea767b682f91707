// The scan engine's extension slots: one per type, O(1), per engine, owned state dropped
// with its engine; hooks attach and detach themselves.
#include <gtest/gtest.h>

#include "plc_cell/core/extension_slots.h"
#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"

namespace plc_cell {
namespace {

struct Counters {
  int n = 0;
};
struct Axes {
  int n = 0;
};
struct Owned {
  static int alive;
  Owned() { ++alive; }
  ~Owned() { --alive; }
  int value = 0;
};
int Owned::alive = 0;

TEST(ExtensionSlots, OneSlotPerTypeEmptyUntilAttached) {
  ExtensionSlots s;
  Counters c;
  Axes a;
  EXPECT_EQ(s.get<Counters>(), nullptr);
  s.attach(&c);
  EXPECT_EQ(s.get<Counters>(), &c);
  EXPECT_EQ(s.get<Axes>(), nullptr);  // another type, another slot
  s.attach(&a);
  EXPECT_EQ(s.get<Axes>(), &a);
  EXPECT_EQ(s.get<Counters>(), &c);
}

TEST(ExtensionSlots, DetachOnlyByItsOwnObject) {
  ExtensionSlots s;
  Counters first, second;
  s.attach(&first);
  s.attach(&second);  // the newer object takes the slot
  s.detach(&first);   // a stale detach leaves it alone
  EXPECT_EQ(s.get<Counters>(), &second);
  s.detach(&second);
  EXPECT_EQ(s.get<Counters>(), nullptr);
}

TEST(ExtensionSlots, OwnedStateIsMadeOnceAndDroppedWithItsSlots) {
  {
    ExtensionSlots s;
    s.owned<Owned>().value = 7;
    EXPECT_EQ(s.owned<Owned>().value, 7);  // the same object on every use
    EXPECT_EQ(Owned::alive, 1);
    s.reset<Owned>();
    EXPECT_EQ(Owned::alive, 0);
    EXPECT_EQ(s.get<Owned>(), nullptr);
    EXPECT_EQ(s.owned<Owned>().value, 0);  // made anew
  }
  EXPECT_EQ(Owned::alive, 0);
}

TEST(ExtensionSlots, ResetLeavesAnAttachedObject) {
  ExtensionSlots s;
  Counters c;
  s.attach(&c);
  s.reset<Counters>();  // not owned: reset is for state the slots made
  EXPECT_EQ(s.get<Counters>(), &c);
}

struct Unit : ScanHook {
  void attached(ScanEngine& e) override { e.extensions().attach(this); }
  void detached(ScanEngine& e) override { e.extensions().detach(this); }
};

TEST(ExtensionSlots, EachEngineHasItsOwnAndHooksAttachThemselves) {
  const FunctionTable fns = FunctionTable::with_core_functions();
  Memory m1, m2;
  ScanEngine e1(m1, fns), e2(m2, fns);
  Unit u;
  e1.add_hook(&u);
  EXPECT_EQ(e1.extensions().get<Unit>(), &u);
  EXPECT_EQ(e2.extensions().get<Unit>(), nullptr);
  e1.remove_hook(&u);
  EXPECT_EQ(e1.extensions().get<Unit>(), nullptr);
  e1.remove_hook(&u);  // not hooked: no second detach
  e2.extensions().owned<Owned>();
  EXPECT_EQ(e1.extensions().get<Owned>(), nullptr);
}

}  // namespace
}  // namespace plc_cell
