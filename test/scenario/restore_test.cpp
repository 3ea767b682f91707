// Leaving a PLC as a case found it (docs/testing-on-hardware.md, "Restore"): each kind of
// point put back, a link that goes down and comes back, one that does not, the user giving
// up, the PLC refusing a point, and the journal that outlives a killed run.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>

#include "memory_plc.h"
#include "plc_cell/scenario/restore.h"

using namespace plc_cell;
using namespace plc_cell::scenario;
using plc_cell::scenario_test::MemoryPlc;

namespace {

TouchedPoint point(const std::string& addr, const std::string& label, bool held) {
  return {parse_address(addr), label, held};
}

std::vector<Address> all(const std::vector<FoundPoint>& found) {
  std::vector<Address> out;
  for (const auto& f : found) out.push_back(f.point.address);
  return out;
}

// The state a case finds: X3 forced ON by someone, R100 = 7, X0 free and OFF, Y1 free and ON.
void found_state(MemoryPlc& m) {
  m.plc.force(parse_address("X3"), ForceAction::Disable);
  m.plc.force(parse_address("X3"), ForceAction::Set);
  m.plc.write(parse_address("R100"), {7});
  m.plc.write(parse_address("Y1"), {1});
}

const std::vector<TouchedPoint> kPoints = {point("X0", "start (X0)", true), point("X3", "part (X3)", true),
                                           point("R100", "R100", false), point("Y1", "lower (Y1)", false)};

// What a case does to them: X0 and X3 forced the other way, R100 and Y1 written.
void the_case(MemoryPlc& m) {
  m.force(parse_address("X0"), true);
  m.force(parse_address("X3"), false);
  m.write(parse_address("R100"), 99);
  m.write(parse_address("Y1"), 0);
  m.log.clear();
}

void expect_as_found(MemoryPlc& m) {
  EXPECT_FALSE(m.disabled("X0"));
  EXPECT_EQ(m.value("X0"), 0u);
  EXPECT_TRUE(m.disabled("X3"));
  EXPECT_EQ(m.value("X3"), 1u);
  EXPECT_EQ(m.value("R100"), 7u);
  EXPECT_EQ(m.value("Y1"), 1u);
}

RestoreOptions no_waiting(int* waits, int* told, bool give_up = false) {
  RestoreOptions o;
  o.wait = [waits, give_up](std::chrono::milliseconds) {
    ++*waits;
    return give_up;
  };
  o.waiting = [told](const std::string&) { ++*told; };
  return o;
}

}  // namespace

TEST(Restore, EveryPointGoesBackAsFoundForcedOrNot) {
  MemoryPlc m;
  found_state(m);
  const auto found = read_found(m, kPoints);
  ASSERT_EQ(found.size(), 4u);
  EXPECT_EQ(found[1].forced, std::optional<bool>(true));
  EXPECT_EQ(found[2].forced, std::nullopt);  // a register has no force
  the_case(m);
  int waits = 0, told = 0;
  const RestoreResult r = restore_points(m, found, all(found), no_waiting(&waits, &told));
  EXPECT_TRUE(r.complete());
  expect_as_found(m);
  EXPECT_EQ(r.restored, (std::vector<std::string>{"start (X0): released, OFF as found", "part (X3): forced ON as found",
                                                  "R100: written back, 7 as found",
                                                  "lower (Y1): written back, ON as found"}));
  EXPECT_EQ(m.log, (std::vector<std::string>{"unforce X0", "write X0 0", "force X3 1", "write R100 7", "write Y1 1"}));
  EXPECT_EQ(waits, 0);
}

TEST(Restore, OnlyWhatTheCaseTouchedIsPutBack) {
  MemoryPlc m;
  found_state(m);
  const auto found = read_found(m, kPoints);
  m.write(parse_address("R100"), 99);  // the case stopped after this write
  m.plc.write(parse_address("Y1"), {0});  // the program's doing, not the case's
  int waits = 0, told = 0;
  const RestoreResult r = restore_points(m, found, {parse_address("R100")}, no_waiting(&waits, &told));
  EXPECT_EQ(r.restored, (std::vector<std::string>{"R100: written back, 7 as found"}));
  EXPECT_EQ(m.value("Y1"), 0u);
}

TEST(Restore, ALinkThatComesBackIsWaitedForAndTheRestoreFinishes) {
  MemoryPlc m;
  found_state(m);
  const auto found = read_found(m, kPoints);
  the_case(m);
  m.fail_next = 3;
  int waits = 0, told = 0;
  const RestoreResult r = restore_points(m, found, all(found), no_waiting(&waits, &told));
  EXPECT_TRUE(r.complete()) << r.not_restored.at(0);
  expect_as_found(m);
  EXPECT_EQ(waits, 3);  // one wait per failed attempt
  EXPECT_EQ(told, 1);   // said once
}

TEST(Restore, ALinkThatStaysDownOrAUserWhoGivesUpLeavesEachPointNamed) {
  for (const bool give_up : {false, true}) {
    MemoryPlc m;
    found_state(m);
    const auto found = read_found(m, kPoints);
    the_case(m);
    m.fail_next = 1000;
    int waits = 0, told = 0;
    RestoreOptions o = no_waiting(&waits, &told, give_up);
    o.retry_for = give_up ? std::chrono::milliseconds(60000) : std::chrono::milliseconds(0);
    const RestoreResult r = restore_points(m, found, all(found), o);
    ASSERT_EQ(r.not_restored.size(), 4u);
    EXPECT_EQ(r.not_restored[0], "start (X0): not put back (the link is down)");
    EXPECT_EQ(r.not_restored[2], "R100: not put back (the link is down)");
    EXPECT_EQ(waits, give_up ? 1 : 0);
  }
}

TEST(Restore, APointThePlcRefusesIsNamedAndTheOthersGoBack) {
  MemoryPlc m;
  found_state(m);
  const auto found = read_found(m, kPoints);
  the_case(m);
  m.refuse_write_of = "R100";
  int waits = 0, told = 0;
  const RestoreResult r = restore_points(m, found, all(found), no_waiting(&waits, &told));
  EXPECT_EQ(r.not_restored, (std::vector<std::string>{"R100: PLC error A (illegal address) to R100"}));
  EXPECT_EQ(r.restored.size(), 3u);
  EXPECT_EQ(m.value("Y1"), 1u);
}

TEST(Restore, AForceThatDidNotGoIsSaidNotRestored) {
  // A link that says it released a point but the PLC keeps it forced (its ENABLE lost).
  class StuckPlc : public MemoryPlc {
   public:
    void unforce(const Address& bit) override { log.push_back("unforce " + format_address(bit) + " (lost)"); }
  } m;
  const auto found = read_found(m, {point("X0", "start (X0)", true)});
  m.force(parse_address("X0"), true);
  int waits = 0, told = 0;
  const RestoreResult r = restore_points(m, found, all(found), no_waiting(&waits, &told));
  EXPECT_EQ(r.not_restored, (std::vector<std::string>{"start (X0): still forced, found not forced"}));
}

TEST(RestoreJournal, WhatARunWroteBeforeItWasKilledIsReadBack) {
  char dir[] = "/tmp/plc_cell_journal_XXXXXX";
  ASSERT_TRUE(::mkdtemp(dir));
  const std::string path = std::string(dir) + "/j";
  MemoryPlc m;
  found_state(m);
  const auto found = read_found(m, kPoints);
  {
    RestoreJournal j(path);
    j.begin("fatek://127.0.0.1:500", "a case", found);
    j.touched(parse_address("X3"));
    j.touched(parse_address("R100"));
  }  // killed: the file stays
  const auto left = RestoreJournal::load(path);
  ASSERT_TRUE(left);
  EXPECT_EQ(left->target, "fatek://127.0.0.1:500");
  EXPECT_EQ(left->case_name, "a case");
  ASSERT_EQ(left->found.size(), 4u);
  EXPECT_EQ(left->found[1].point.label, "part (X3)");
  EXPECT_EQ(left->found[1].forced, std::optional<bool>(true));
  EXPECT_TRUE(left->found[1].point.held);
  EXPECT_EQ(left->found[2].value, 7u);
  EXPECT_EQ(left->found[2].forced, std::nullopt);
  EXPECT_EQ(left->touched, (std::vector<Address>{parse_address("X3"), parse_address("R100")}));
  RestoreJournal(path).remove();
  EXPECT_FALSE(RestoreJournal::load(path));
  std::ofstream(path) << "plc_cell restore journal 1\nfound Q9 1 0 0 x\n";
  try {
    RestoreJournal::load(path);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ":2: ", 0), 0u) << e.what();
  }
  std::remove(path.c_str());
  ::rmdir(dir);
}
