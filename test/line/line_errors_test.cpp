// Every bad line file is an error at the file:line:column that causes it (docs/lines.md,
// "Errors"), all of a file's errors in one run; a cell YAML's or a program's own errors at
// their own lines.
#include <gtest/gtest.h>

#include <fstream>
#include <random>

#include "line_fixture.h"

namespace plc_cell {
namespace testing {
namespace {

// A folder with two good cells (a: Y0 = X20, signals part_out: Y0, part_in: X20) and the
// line file `line`.
std::string errors_of(const std::string& name, const std::string& line,
                      std::map<std::string, std::string> more = {}) {
  std::map<std::string, std::string> files = {
      {"copy.il", "ORG X20\nOUT Y0\nEND\n"},
      {"a.yaml", cell_yaml("a", "copy.il", "0.001", "signals: {part_out: Y0, part_in: X20, busy: M5}\n")},
      {"b.yaml", cell_yaml("b", "copy.il", "0.001", "signals: {part_out: Y0, part_in: X20}\n")},
      {"l.line.yaml", line}};
  for (auto& m : more) files[m.first] = m.second;
  LineFolder f(name, files);
  std::string s = line_errors(f.path("l.line.yaml"));
  // Paths relative to the folder, for the expectations.
  for (size_t at; (at = s.find(f.dir() + "/")) != std::string::npos;) s.erase(at, f.dir().size() + 1);
  return s;
}

const std::string kCells = "cells:\n  a: a.yaml\n  b: b.yaml\nwires:\n";

TEST(LineErrors, TheFilesShape) {
  EXPECT_EQ(errors_of("shape", "- a\n"), "l.line.yaml:1:1: error: a line file is a mapping with 'cells' and 'wires'\n");
  EXPECT_EQ(errors_of("keys", "cells: {a: a.yaml}\nwire: []\n"),
            "l.line.yaml:2:1: error: key 'wire': unknown key (expected one of: cells, line, wires)\n");
  EXPECT_EQ(errors_of("no_cells", "wires: []\n"),
            "l.line.yaml:1:1: error: key 'cells': expected a mapping of cell names to cell YAMLs (robot: robot.yaml)\n");
  EXPECT_EQ(errors_of("cell_name", "cells:\n  a-1: a.yaml\n"),
            "l.line.yaml:2:3: error: key 'cells.a-1': a cell name is letters, digits and _ (it becomes a ROS topic name)\n");
  EXPECT_EQ(errors_of("cell_keys", "cells:\n  a: {config: a.yaml, programme: x.il}\n"),
            "l.line.yaml:2:23: error: key 'cells.a.programme': unknown key (expected one of: config, program, scan)\n");
  EXPECT_EQ(errors_of("cell_config", "cells:\n  a: {program: copy.il}\n"),
            "l.line.yaml:2:6: error: key 'cells.a': missing 'config': the cell YAML\n");
  EXPECT_EQ(errors_of("cell_scan", "cells:\n  a: {config: a.yaml, scan: 5s}\n"),
            "l.line.yaml:2:29: error: key 'cells.a.scan': a scan period is 0.1 ms to 1 s\n");
  EXPECT_EQ(errors_of("wires_list", "cells: {a: a.yaml}\nwires: {from: a.Y0}\n"),
            "l.line.yaml:2:8: error: key 'wires': expected a list of {from: CELL.NAME, to: CELL.NAME}\n");
}

TEST(LineErrors, AWiresOwnKeys) {
  EXPECT_EQ(errors_of("wire_map", kCells + "  - a.Y0\n"),
            "l.line.yaml:5:5: error: key 'wires[0]': a wire is a mapping: {from: CELL.NAME, to: CELL.NAME, delay: 2s}\n");
  EXPECT_EQ(errors_of("wire_key", kCells + "  - {from: a.Y0, to: b.X20, dealy: 2s}\n"),
            "l.line.yaml:5:29: error: key 'wires[0].dealy': unknown key (expected one of: delay, from, invert, part, to)\n");
  EXPECT_EQ(errors_of("wire_to", kCells + "  - {from: a.Y0}\n"),
            "l.line.yaml:5:5: error: key 'wires[0]': missing 'to': CELL.NAME, e.g. robot.part_in\n");
  EXPECT_EQ(errors_of("unqualified", kCells + "  - {from: Y0, to: b.X20}\n"),
            "l.line.yaml:5:12: error: key 'wires[0].from': 'Y0': a wire's end is CELL.NAME (a signal or an address of the "
            "cell: robot.part_in, robot.X3)\n");
  EXPECT_EQ(errors_of("delay_text", kCells + "  - {from: a.Y0, to: b.X20, delay: soon}\n"),
            "l.line.yaml:5:36: error: key 'wires[0].delay': bad duration 'soon' (examples: 2.5s, 100ms, 500us)\n");
  EXPECT_EQ(errors_of("delay_long", kCells + "  - {from: a.Y0, to: b.X20, delay: 2h}\n"),
            "l.line.yaml:5:36: error: key 'wires[0].delay': bad duration '2h': unit must be s, ms, us or min\n");
  EXPECT_EQ(errors_of("delay_hour", kCells + "  - {from: a.Y0, to: b.X20, delay: 3601s}\n"),
            "l.line.yaml:5:36: error: key 'wires[0].delay': at most 3600 s\n");
  EXPECT_EQ(errors_of("part_length", kCells + "  - {from: a.Y0, to: b.X20, part: {travel: 1s, length: 0s}}\n"),
            "l.line.yaml:5:56: error: key 'wires[0].part.length': a part covers its sensor for some time: above 0\n");
  EXPECT_EQ(errors_of("part_half", kCells + "  - {from: a.Y0, to: b.X20, part: {travel: 1s}}\n"),
            "l.line.yaml:5:35: error: key 'wires[0].part': a part has a travel and a length: {travel: 2s, length: 300ms}\n");
  EXPECT_EQ(errors_of("part_delay", kCells + "  - {from: a.Y0, to: b.X20, delay: 1s, part: {travel: 1s, length: 1s}}\n"),
            "l.line.yaml:5:36: error: key 'wires[0].delay': a part's delay is its travel: part: {travel: 2s, length: 300ms}\n");
}

TEST(LineErrors, NamesTheirCellsDoNotHave) {
  EXPECT_EQ(errors_of("cell", kCells + "  - {from: a.Y0, to: c.X20}\n"),
            "l.line.yaml:5:22: error: 'c.X20': no cell 'c' in the line (a, b)\n");
  EXPECT_EQ(errors_of("signal", kCells + "  - {from: a.part_outt, to: b.part_in}\n"),
            "l.line.yaml:5:12: error: 'a.part_outt': 'part_outt' is neither a signal of cell a nor an address "
            "('part_outt': unknown prefix (expected X, Y, M, S, T, C, RT, RC, R, D, F, a W/DW view such as WX8 or DWM0, "
            "or a 32-bit register such as DR0, DD0, DF0, DRT0, DRC200))\n");
  EXPECT_EQ(errors_of("address", kCells + "  - {from: a.Y0, to: b.X300}\n"),
            "l.line.yaml:5:22: error: 'b.X300': 'X300' is neither a signal of cell b nor an address ('X300': out of "
            "range: X has elements 0..255)\n");
}

TEST(LineErrors, WhatAWireMayNotDrive) {
  const std::string may = ": a wire drives an input (X), a relay (M, S) or a register (R, D)\n";
  EXPECT_EQ(errors_of("output", kCells + "  - {from: a.part_out, to: b.part_out}\n"),
            "l.line.yaml:5:28: error: 'b.part_out' (Y0) is an output" + may);
  EXPECT_EQ(errors_of("timer", kCells + "  - {from: a.Y0, to: b.T3}\n"),
            "l.line.yaml:5:22: error: 'b.T3' (T3) is a timer or counter contact" + may);
  EXPECT_EQ(errors_of("counter_value", kCells + "  - {from: a.R0, to: b.RC3}\n"),
            "l.line.yaml:5:22: error: 'b.RC3' (RC3) is a timer or counter value" + may);
  EXPECT_EQ(errors_of("special", kCells + "  - {from: a.Y0, to: b.M1924}\n"),
            "l.line.yaml:5:22: error: 'b.M1924' (M1924) is a special relay of the PLC\n");
  EXPECT_EQ(errors_of("special_r", kCells + "  - {from: a.DR0, to: b.DR3839}\n"),
            "l.line.yaml:5:23: error: 'b.DR3839' (DR3839) is a special or read-only register (R3840 and up)\n");
  EXPECT_EQ(errors_of("group", kCells + "  - {from: a.WY0, to: b.WX0}\n"),
            "l.line.yaml:5:23: error: 'b.WX0' (WX0) is 16 or 32 points: a wire drives one input or relay\n");
}

TEST(LineErrors, OneWirePerSink) {
  // b.part_in is X20: by its name and by its address it is one input.
  EXPECT_EQ(errors_of("twice", kCells + "  - {from: a.Y0, to: b.part_in}\n  - {from: a.M5, to: b.X20}\n"),
            "l.line.yaml:6:22: error: 'b.X20' (X20) is driven already, by the wire at l.line.yaml:5\n");
}

TEST(LineErrors, BitsToBitsRegistersToRegistersOfTheirWidth) {
  EXPECT_EQ(errors_of("width", kCells + "  - {from: a.R0, to: b.DD0}\n"),
            "l.line.yaml:5:22: error: 'a.R0' is 16 bits, 'b.DD0' 32 bits: a wire joins a bit to a bit, a register to a "
            "register of its width\n");
  EXPECT_EQ(errors_of("bit_word", kCells + "  - {from: a.Y0, to: b.R0}\n"),
            "l.line.yaml:5:22: error: 'a.Y0' is a bit, 'b.R0' 16 bits: a wire joins a bit to a bit, a register to a "
            "register of its width\n");
  EXPECT_EQ(errors_of("invert_word", kCells + "  - {from: a.R0, to: b.R1, invert: true}\n"),
            "l.line.yaml:5:5: error: a register's wire carries its value: 'invert' is for a bit\n");
}

TEST(LineErrors, AnInputTheCellsSimulationOrAPulseSourcePlays) {
  EXPECT_EQ(errors_of("simulated", kCells + "  - {from: a.Y0, to: b.part_in}\n",
                      {{"b.yaml", cell_yaml("b", "copy.il", "0.001",
                                            "signals: {part_in: X20}\nsimulation:\n  inputs:\n    part_in: {steps: [[1, 1]]}\n")}}),
            "l.line.yaml:5:22: error: 'b.part_in' (X20) is played by the simulation of b.yaml (simulation.inputs.part_in): "
            "a wired input has no simulation of its own\n");
  EXPECT_EQ(errors_of("encoder", kCells + "  - {from: a.Y0, to: b.X0}\n",
                      {{"b.yaml", cell_yaml("b", "copy.il", "0.001",
                                            "counters:\n  hsc0: {mode: MD7}\n  sources:\n"
                                            "    - {name: enc, type: encoder, a: X0, hz: 1000}\n")}}),
            "l.line.yaml:5:22: error: 'b.X0' (X0) is driven by a pulse source of the cell's counters or axes\n");
}

TEST(LineErrors, ACellsOwnErrorsAtTheirOwnLinesAndEveryErrorAtOnce) {
  // b.yaml has a bad scan period (its line 2) and its program a bad instruction (line 2);
  // the line's wire names a signal a lacks: three errors, each where it is.
  const std::string s = errors_of("all", kCells + "  - {from: a.nothing, to: b.X20}\n",
                                  {{"bad.il", "ORG X20\nOUTT Y0\nEND\n"},
                                   {"b.yaml", "cell: {name: b, program: bad.il}\nplc: {scan_period: 7}\n"}});
  EXPECT_NE(s.find("b.yaml:2:20: error: key 'plc.scan_period': value 7 out of range [0.0001, 1]\n"), std::string::npos) << s;
  EXPECT_NE(s.find("l.line.yaml:5:12: error: 'a.nothing': "), std::string::npos) << s;
}

TEST(LineErrors, AProgramsErrorAtItsLine) {
  const std::string s = errors_of("program", kCells, {{"bad.il", "ORG X20\nOUTT Y0\nEND\n"},
                                                       {"b.yaml", cell_yaml("b", "bad.il")}});
  EXPECT_EQ(s.substr(0, s.find("error")), "bad.il:2:1: ") << s;
}

TEST(LineErrors, FilesThatCannotBeOpened) {
  EXPECT_EQ(errors_of("missing", "cells:\n  a: nowhere.yaml\n  b: {config: b.yaml, program: none.il}\n"),
            "l.line.yaml:2:6: error: key 'cells.a': cannot open the cell YAML: No such file or directory (looked for "
            "nowhere.yaml)\n"
            "l.line.yaml:3:32: error: key 'cells.b.program': cannot open the program: No such file or directory (looked "
            "for none.il)\n");
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell

namespace plc_cell {
namespace testing {
namespace {

// Random damage to a good line file (a byte changed, dropped or doubled, from a fixed seed):
// reading and building it either succeeds or throws SourceError, each error naming a file,
// and nothing else escapes.
TEST(LineErrors, DamagedFilesAreErrorsNeverCrashes) {
  const std::string good = "line: {name: l}\ncells:\n  a: a.yaml\n  b: {config: b.yaml, scan: 2ms}\nwires:\n"
                           "  - {from: a.Y0, to: b.X20, delay: 5ms}\n  - {from: b.Y0, to: a.X3, invert: true}\n"
                           "  - {from: a.M5, to: b.X21, part: {travel: 1s, length: 20ms}}\n  - {from: a.R0, to: b.D7}\n";
  LineFolder f("hostile", {{"copy.il", "ORG X20\nOUT Y0\nEND\n"},
                           {"a.yaml", cell_yaml("a", "copy.il")},
                           {"b.yaml", cell_yaml("b", "copy.il")}});
  std::mt19937 rnd(20240601);
  const std::string chars = "{}[]:,.-#&*!|>'\"%@` \n\tabXYRD0123456789";
  int refused = 0;
  for (int i = 0; i < 600; ++i) {
    std::string text = good;
    for (int k = 0, edits = 1 + int(rnd() % 3); k < edits; ++k) {
      const size_t at = rnd() % text.size();
      switch (rnd() % 3) {
        case 0: text[at] = chars[rnd() % chars.size()]; break;
        case 1: text.erase(at, 1); break;
        default: text.insert(at, 1, text[at]);
      }
    }
    std::ofstream(f.path("l.line.yaml")) << text;
    try {
      line::Line l(f.path("l.line.yaml"));
      l.run();
      if (i % 2)
        l.advance(0, 5000);  // as plc_cell sim runs it: cell by cell
      else
        for (uint64_t t = 0; t < 5000; t += l.tick_us()) l.scan_at(t);
    } catch (const SourceError& e) {
      ++refused;
      for (const auto& d : e.diagnostics()) {
        ASSERT_FALSE(d.where.file.empty()) << d.to_string() << "\n" << text;
        ASSERT_FALSE(d.message.empty()) << text;
      }
    }
  }
  EXPECT_GT(refused, 300);  // most damage breaks the flow mappings; the rest still makes a line
  EXPECT_LT(refused, 600) << "no damaged file made a line";
}

}  // namespace
}  // namespace testing
}  // namespace plc_cell
