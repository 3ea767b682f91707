// What the recorder counts, checked against programs whose every contact, coil and FUN
// value is worked out by hand from the scans below (docs/coverage.md has the definitions).
#include "plc_cell/coverage/recorder.h"

#include "plc_cell/core/error.h"
#include "plc_cell/coverage/recorders.h"
#include "coverage_fixture.h"

namespace plc_cell {
namespace coverage {
namespace {

using Coverage = CoverageTest;

TEST_F(Coverage, NetworksEnergisedContactsChangedCoilsSwitched) {
  Recorder rec;
  run_case(rec, write("two.il", kTwoNetworks), {{{0, true}}, {{0, false}}});  // Y0's rung ON, then OFF
  const Report r = report(rec);

  ASSERT_EQ(r.networks.size(), 2u);
  EXPECT_TRUE(network(r, 1).evaluated);
  EXPECT_TRUE(network(r, 1).energised);
  EXPECT_EQ(network(r, 1).line, 2);
  EXPECT_EQ(network(r, 1).end_line, 4);
  EXPECT_TRUE(network(r, 2).evaluated);
  EXPECT_FALSE(network(r, 2).energised);
  EXPECT_EQ(seen(item(r, 2)), "off+on");  // X0
  EXPECT_EQ(seen(item(r, 3)), "off");     // the device X1, not the NOT contact's result
  EXPECT_EQ(seen(item(r, 4)), "off+on");  // OUT Y0
  EXPECT_EQ(seen(item(r, 5)), "off");     // X2
  EXPECT_EQ(seen(item(r, 6)), "off");     // OUT Y1
  EXPECT_EQ(item(r, 3).name, "X1");
  EXPECT_EQ(item(r, 4).name, "OUT Y0");
  EXPECT_EQ(item(r, 4).kind, ItemKind::Coil);

  EXPECT_EQ(totals(r), "networks evaluated 2/2, energised 1/2, contacts changed 1/3, coils switched 1/2, "
                      "FUNs enabled 0/0");
  EXPECT_EQ(findings(r), (std::vector<std::string>{"3: contact X1 never changed (always OFF)",
                                                   "5: network 2 never energised",
                                                   "5: contact X2 never changed (always OFF)",
                                                   "6: coil OUT Y1 never switched (rung always OFF)"}));
  EXPECT_EQ(r.source.size(), 7u);
  EXPECT_EQ(r.source[4], "ORG X2      ; never pressed");
  EXPECT_EQ(r.source_error, "");
}

TEST_F(Coverage, CodeJumpedOverIsNotEvaluated) {
  const std::string path = write("jump.il",
                                 "ORG M1925\n"
                                 "JMP SKIP\n"
                                 "ORG X0\n"
                                 "OUT Y0\n"
                                 "LBL SKIP\n"
                                 "ORG X1\n"
                                 "OUT Y1\n"
                                 "END\n");
  Recorder rec;
  run_case(rec, path, {{{1, true}}, {{1, false}}});
  const Report r = report(rec);

  ASSERT_EQ(r.networks.size(), 3u);
  EXPECT_TRUE(network(r, 1).energised);  // JMP's EN was ON
  EXPECT_FALSE(network(r, 2).evaluated);
  EXPECT_FALSE(network(r, 2).energised);
  EXPECT_EQ(network(r, 2).end_line, 4);  // the LBL closes it
  EXPECT_TRUE(network(r, 3).energised);
  EXPECT_EQ(item(r, 2).kind, ItemKind::Fun);
  EXPECT_EQ(item(r, 2).name, "JMP SKIP");
  EXPECT_EQ(seen(item(r, 2)), "on");
  EXPECT_EQ(seen(item(r, 3)), "none");
  EXPECT_EQ(seen(item(r, 4)), "none");
  // Contacts X0 and X1 (M1925, always ON, cannot change: not measured).
  EXPECT_EQ(totals(r), "networks evaluated 2/3, energised 2/3, contacts changed 1/2, coils switched 1/2, "
                      "FUNs enabled 1/1");
  // Network 2 is one finding: nothing of what it holds is listed.
  EXPECT_EQ(findings(r), (std::vector<std::string>{"3: network 2 not evaluated"}));
}

TEST_F(Coverage, SubroutinesAndInterruptRoutinesCount) {
  const std::string path = write("routines.il",
                                 "ORG X0\n"
                                 "CALL SUB\n"
                                 "END\n"
                                 "LBL SUB\n"
                                 "ORG X1\n"
                                 "OUT Y0\n"
                                 "RTS\n"
                                 "LBL X0+I\n"
                                 "ORG M1925\n"
                                 "OUT Y1\n"
                                 "RTI\n"
                                 "LBL UNUSED\n"
                                 "ORG M1925\n"
                                 "OUT Y2\n"
                                 "RTS\n");
  auto plc = plc_running(path);
  Recorder rec;
  rec.attach(*plc);
  scan(*plc, {{0, true}, {1, true}});
  scan(*plc, {{1, false}});
  const bool ran = plc->locked([](ScanEngine& e, Memory&) {
    return e.interpreter().run_routine("X0+I", e.now_us(), &e);
  });
  EXPECT_TRUE(ran);
  rec.detach(*plc);
  const Report r = report(rec);

  ASSERT_EQ(r.networks.size(), 4u);
  EXPECT_EQ(network(r, 1).routine, "");
  EXPECT_EQ(network(r, 2).routine, "SUB");
  EXPECT_EQ(network(r, 3).routine, "X0+I");
  EXPECT_EQ(network(r, 4).routine, "UNUSED");
  EXPECT_EQ(item(r, 2).name, "CALL SUB");
  EXPECT_EQ(seen(item(r, 2)), "on");
  EXPECT_TRUE(network(r, 2).energised);
  EXPECT_EQ(seen(item(r, 5)), "off+on");  // X1 in the subroutine
  EXPECT_EQ(seen(item(r, 6)), "off+on");
  EXPECT_TRUE(network(r, 3).evaluated);   // through run_routine only
  EXPECT_EQ(seen(item(r, 10)), "on");
  EXPECT_FALSE(network(r, 4).evaluated);
  EXPECT_EQ(totals(r), "networks evaluated 3/4, energised 3/4, contacts changed 1/2, coils switched 1/3, "
                      "FUNs enabled 1/1");
  EXPECT_EQ(findings(r), (std::vector<std::string>{"1: contact X0 never changed (always ON)",
                                                   "10: coil OUT Y1 never switched (rung always ON)",
                                                   "13: network 4 not evaluated"}));
}

TEST_F(Coverage, FunsTimersCountersSetAndReset) {
  const std::string path = write("funs.il",
                                 "ORG X0\n"
                                 "MOV S=K5 D=R0\n"
                                 "ORG X1\n"
                                 "ADD Sa=R0 Sb=1 D=R1\n"
                                 "ORG X0\n"
                                 "TMR T0 10\n"
                                 "ORG X0\n"
                                 "CTR C0 3\n"
                                 "ORG X0\n"
                                 "SET M0\n"
                                 "ORG X1\n"
                                 "RST M0\n"
                                 "ORG X0\n"
                                 "FUN 8P S=K7 D=R2\n"
                                 "END\n");
  Recorder rec;
  run_case(rec, path, {{{0, true}}, {{0, false}}});
  const Report r = report(rec);

  EXPECT_EQ(item(r, 2).name, "FUN 8 MOV");
  EXPECT_EQ(seen(item(r, 2)), "off+on");
  EXPECT_EQ(item(r, 4).name, "FUN 11 ADD");
  EXPECT_EQ(seen(item(r, 4)), "off");
  EXPECT_FALSE(item(r, 4).exercised());
  EXPECT_EQ(item(r, 6).name, "TMR T0");
  EXPECT_EQ(seen(item(r, 6)), "off+on");
  EXPECT_EQ(item(r, 8).name, "CTR C0");
  EXPECT_EQ(seen(item(r, 8)), "off+on");
  EXPECT_EQ(item(r, 10).name, "SET M0");
  EXPECT_EQ(seen(item(r, 10)), "off+on");
  EXPECT_EQ(item(r, 12).name, "RST M0");
  EXPECT_EQ(seen(item(r, 12)), "off");
  EXPECT_EQ(item(r, 14).name, "FUN 8P MOV");
  EXPECT_EQ(seen(item(r, 14)), "off+on");  // EN itself, not its rising edge
  // Networks 2 and 6 (ORG X1) never energised; X1 in both never changed; of the coils TMR,
  // CTR, SET switched and RST did not; MOV and MOV.P enabled, ADD not.
  EXPECT_EQ(totals(r), "networks evaluated 7/7, energised 5/7, contacts changed 5/7, coils switched 3/4, "
                      "FUNs enabled 2/3");
  EXPECT_EQ(findings(r), (std::vector<std::string>{"3: network 2 never energised",
                                                   "3: contact X1 never changed (always OFF)",
                                                   "4: FUN 11 ADD never enabled",
                                                   "11: network 6 never energised",
                                                   "11: contact X1 never changed (always OFF)",
                                                   "12: coil RST M0 never switched (rung always OFF)"}));
}

const char* const kTwoOutputs =
    "ORG X0\n"
    "OUT Y0\n"
    "ORG X1\n"
    "OUT Y1\n"
    "END\n";

TEST_F(Coverage, RunsOfFreshPlcsAreSummed) {
  const std::string path = write("merge.il", kTwoOutputs);
  Recorder rec;
  run_case(rec, path, {{{0, true}}, {}});  // case 1 presses X0 only; its PLC is gone, its recording stays
  const Report first = report(rec);
  EXPECT_TRUE(network(first, 1).energised);
  EXPECT_FALSE(network(first, 2).energised);
  EXPECT_EQ(seen(item(first, 1)), "on");

  run_case(rec, path, {{{1, true}}});  // case 2 presses X1 only
  const Report both = report(rec);
  EXPECT_EQ(both.runs, 2u);
  EXPECT_TRUE(network(both, 1).energised);
  EXPECT_TRUE(network(both, 2).energised);
  // Seen both values over the run: ON in one case, OFF in the other.
  EXPECT_EQ(seen(item(both, 1)), "off+on");
  EXPECT_EQ(seen(item(both, 3)), "off+on");
  EXPECT_EQ(seen(item(both, 2)), "off+on");
  EXPECT_TRUE(both.findings.empty());
}

TEST_F(Coverage, SeveralPlcsRecordAtOnce) {
  const std::string path = write("merge.il", kTwoOutputs);
  auto a = plc_running(path);
  auto b = plc_running(path);
  Recorder rec;
  rec.attach(*a);
  rec.attach(*b);
  scan(*a, {{0, true}});
  scan(*b, {{1, true}});
  rec.detach(*b);
  rec.detach(*a);
  const Report r = report(rec);
  EXPECT_EQ(r.runs, 2u);
  EXPECT_EQ(r.totals.networks_energised, 2u);
}

TEST_F(Coverage, AnotherProgramIsRefused) {
  const std::string path = write("a.il", kTwoOutputs);
  auto a = plc_running(path);
  Recorder rec;
  rec.attach(*a);

  write("a.il", "ORG X0\nOUT Y0\nORG X1\nOUT Y2\nEND\n");  // the file was edited
  auto edited = plc_running(path);
  try {
    rec.attach(*edited);
    FAIL() << "an edited program was accepted";
  } catch (const Error& e) {
    EXPECT_EQ(std::string(e.what()), "coverage: " + path + " is not the program this recorder holds (" + path +
                                         "): instruction 4 is OUT Y2 on line 4, not OUT Y1 on line 4; record each "
                                         "program with its own recorder");
  }
  auto other = plc_running(write("b.il", kTwoOutputs));  // same text, another file
  EXPECT_THROW(rec.attach(*other), Error);
  try {
    rec.attach(*other);
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("it is another file"), std::string::npos) << e.what();
  }
  // Neither was recorded: they scan as before and detach adds nothing.
  scan(*edited, {{1, true}});
  rec.detach(*edited);
  rec.detach(*a);
  EXPECT_EQ(report(rec).runs, 1u);
  EXPECT_EQ(edited->locked([](ScanEngine& e, Memory&) { return e.interpreter().recording(); }), nullptr);
}

TEST_F(Coverage, AttachAndDetachRules) {
  Recorder rec;
  EXPECT_TRUE(rec.empty());
  EXPECT_EQ(rec.program_file(), "");
  EXPECT_THROW(report(rec), Error);
  Plc bare;
  EXPECT_THROW(rec.attach(bare), Error);  // no program
  EXPECT_TRUE(rec.empty());

  const std::string path = write("a.il", kTwoOutputs);
  auto plc = plc_running(path);
  rec.attach(*plc);
  EXPECT_FALSE(rec.empty());
  EXPECT_EQ(rec.program_file(), path);
  EXPECT_THROW(rec.attach(*plc), Error);  // already attached here
  Recorder other;
  EXPECT_THROW(other.attach(*plc), Error);  // and recorded elsewhere
  rec.detach(*plc);
  rec.detach(*plc);  // twice is harmless
  rec.detach(bare);  // never attached: nothing to do
  EXPECT_EQ(rec.runs(), 1u);
  other.attach(*plc);  // free again
  other.detach(*plc);
}

TEST_F(Coverage, LoadingAnotherProgramEndsTheRecording) {
  const std::string path = write("a.il", kTwoOutputs);
  auto plc = plc_running(path);
  Recorder rec;
  rec.attach(*plc);
  scan(*plc, {{0, true}});
  plc->load_program_file(write("b.il", "ORG X1\nOUT Y5\nEND\n"));
  EXPECT_EQ(plc->locked([](ScanEngine& e, Memory&) { return e.interpreter().recording(); }), nullptr);
  scan(*plc, {{0, false}, {1, true}});
  rec.detach(*plc);
  const Report r = report(rec);
  EXPECT_EQ(r.file, path);
  EXPECT_EQ(seen(item(r, 1)), "on");  // what a.il saw before the load, nothing after
  EXPECT_EQ(seen(item(r, 3)), "off");
}

TEST_F(Coverage, RecordingDoesNotChangeWhatThePlcDoes) {
  const std::string path = write("mixed.il",
                                 "ORG X0\nAND TU X1\nOR NOT X2\nLD X3\nOR M5\nANDLD\nOUT Y0\nSET M5\n"
                                 "ORG X1\nTMR T0 3\nORG T0\nCTR C0 2\nORG X2\nADD Sa=R0 Sb=3 D=R0\n"
                                 "ORG C0\nRST M5\nRST C0\nEND\n");
  auto plain = plc_running(path);
  auto recorded = plc_running(path);
  Recorder rec;
  rec.attach(*recorded);
  for (int k = 0; k < 200; ++k) {
    const uint64_t t = now_us;
    for (Plc* p : {plain.get(), recorded.get()}) {
      for (uint32_t x = 0; x < 4; ++x) p->set_input(x, ((k >> x) ^ (k / 7)) & 1);
      p->scan(t);
    }
    now_us += 10000;
    for (const char* a : {"WY0", "WM0", "R0", "RT0", "RC0", "WT0", "WC0"})
      ASSERT_EQ(plain->read(parse_address(a), 1), recorded->read(parse_address(a), 1)) << a << " at scan " << k;
  }
  rec.detach(*recorded);
  // X1 is on for four scans from scans 12, 40, 68, ...: T0 (30 ms) runs out at scans 15 and
  // 43, so C0 reaches 2 at scan 43 and the last network is energised too.
  EXPECT_EQ(report(rec).totals.networks_energised, 5u);
}

TEST_F(Coverage, WithoutItsSourceTheReportShowsTheParsedInstructions) {
  Plc plc;
  plc.load_program_text("ORG X0  ; start\nOUT Y0\nEND\n", dir + "/gone.il");
  ASSERT_TRUE(plc.set_mode(RunMode::Run));
  Recorder rec;
  rec.attach(plc);
  scan(plc);
  rec.detach(plc);
  const Report r = report(rec);
  EXPECT_EQ(r.source_error, "cannot read " + dir + "/gone.il: No such file or directory");
  EXPECT_EQ(r.source, (std::vector<std::string>{"ORG X0", "OUT Y0", "END"}));
}

TEST_F(Coverage, RecordersKeepOneRecorderPerProgram) {
  const std::string a = write("a.il", kTwoOutputs);
  const std::string b = write("b.il", "ORG X0\nOUT Y0\nEND\n");
  Recorders all;
  for (const std::string& path : {b, a, a}) {
    auto plc = plc_running(path);
    all.attach(*plc);
    scan(*plc);
    all.detach(*plc);
  }
  Plc bare;
  EXPECT_THROW(all.attach(bare), Error);
  const std::vector<Report> reports = all.reports();
  ASSERT_EQ(reports.size(), 2u);  // the PLC without a program left no recorder
  EXPECT_EQ(reports[0].file, a);  // by file name
  EXPECT_EQ(reports[0].runs, 2u);
  EXPECT_EQ(reports[1].file, b);
  EXPECT_EQ(reports[1].runs, 1u);

  write("a.il", "ORG X0\nOUT Y3\nEND\n");  // edited during the run
  auto edited = plc_running(a);
  EXPECT_THROW(all.attach(*edited), Error);
}

}  // namespace
}  // namespace coverage
}  // namespace plc_cell
