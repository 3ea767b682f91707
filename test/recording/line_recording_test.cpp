// A line's recording (docs/recordings.md, "A line's recording"): each cell's run as a lone
// cell's under the line, read back whole; every damage refused with its offset; each reader
// telling the other kind of file apart.
#include <gtest/gtest.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/recording/envelope.h"
#include "plc_cell/recording/line_recording.h"

namespace plc_cell {
namespace {

recording::RecordingInfo info(const std::string& program, uint64_t period_us) {
  recording::RecordingInfo i;
  i.source = "test";
  i.program_file = program;
  i.program_text = "ORG X0\nOUT Y0\nEND\n";
  i.signals = {{"go", parse_address("X0")}};
  i.scan_period_us = period_us;
  return i;
}

// Two PLCs: a (1 ms, Y0 follows X0, turned on after its third scan) and b (2 ms), 10 ms.
std::string two_cell_recording() {
  Plc a, b;
  for (Plc* p : {&a, &b}) {
    p->load_program_text("ORG X0\nOUT Y0\nEND\n", "p.il");
    p->set_mode(RunMode::Run);
  }
  recording::LineRecordingInfo li;
  li.source = "test";
  li.line = "two";
  li.wires = {"a.Y0 -> b.X0"};
  recording::LineRecorder rec(li, {{"a", info("a.il", 1000)}, {"b", info("b.il", 2000)}});
  rec.cell(0).start(a);
  rec.cell(1).start(b);
  for (uint64_t t = 0; t < 10000; t += 1000) {
    a.scan(t);
    rec.cell(0).scanned(a, t);
    if (t == 2000) a.set_input(0, true);
    if (t % 2000 == 0) {
      b.scan(t);
      rec.cell(1).scanned(b, t);
    }
  }
  rec.set_failure(9000, "s.yaml:3: expect b.Y0");
  return rec.bytes();
}

std::string error_of(const std::string& bytes) {
  try {
    recording::LineReader::parse(bytes, "line.plcrec");
  } catch (const recording::RecordingError& e) {
    return e.what();
  }
  return "";
}

TEST(LineRecording, EachCellsRunReadsBackUnderTheLine) {
  const std::string bytes = two_cell_recording();
  EXPECT_EQ(recording::format_version(bytes), recording::kLineFormatVersion);
  const auto r = recording::LineReader::parse(bytes, "line.plcrec");
  EXPECT_EQ(r.info().line, "two");
  EXPECT_EQ(r.info().wires, std::vector<std::string>{"a.Y0 -> b.X0"});
  ASSERT_TRUE(r.info().failure_us.has_value());
  EXPECT_EQ(*r.info().failure_us, 9000u);
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.name(0), "a");
  EXPECT_EQ(r.cell(0).scans(), 10u);  // 0, 1, ..., 9 ms
  EXPECT_EQ(r.cell(1).scans(), 5u);   // 0, 2, ..., 8 ms
  EXPECT_EQ(r.cell(1).info().scan_period_us, 2000u);
  EXPECT_EQ(r.cell(1).info().failure, "s.yaml:3: expect b.Y0");  // each cell carries the failure
  // a's Y0 turned on at its 3 ms scan (X0 set after the 2 ms one).
  const auto y0 = recording::cells_of(parse_address("Y0"));
  recording::Image img;
  r.cell(0).image_after(2, &img);
  EXPECT_EQ(img.bits[y0[0]] & 1, 0);
  r.cell(0).image_after(3, &img);
  EXPECT_EQ(img.bits[y0[0]] & 1, 1);
  EXPECT_EQ(r.find("b"), &r.cell(1));
  EXPECT_EQ(r.find("c"), nullptr);
}

TEST(LineRecording, EveryTruncationAndEveryCutPayloadIsRefusedWithItsOffset) {
  const std::string bytes = two_cell_recording();
  for (size_t n = 0; n < bytes.size(); ++n) {
    const std::string e = error_of(bytes.substr(0, n));
    ASSERT_EQ(e.rfind("line.plcrec: offset ", 0), 0u) << "cut at " << n << ": '" << e << "'";
  }
  const std::string payload = recording::unpack(bytes, "x", recording::kLineFormatVersion);
  for (size_t n = 0; n < payload.size(); n += 7) {
    const std::string e = error_of(recording::pack(payload.substr(0, n), recording::kLineFormatVersion));
    ASSERT_NE(e, "") << "payload cut at " << n;
    ASSERT_EQ(e.rfind("line.plcrec", 0), 0u) << e;
  }
  EXPECT_NE(error_of(recording::pack(payload + "zz", recording::kLineFormatVersion)).find("2 bytes after the last cell"),
            std::string::npos);
}

TEST(LineRecording, EachReaderSaysWhatTheOtherKindOfFileIs) {
  Plc p;
  p.load_program_text("END\n", "p.il");
  recording::Recorder one(info("p.il", 1000));
  one.start(p);
  EXPECT_EQ(error_of(one.bytes()), "line.plcrec: offset 8: a recording of one cell, not of a line");
  try {
    recording::Reader::parse(two_cell_recording(), "line.plcrec");
    ADD_FAILURE() << "a cell's reader read a line's recording";
  } catch (const recording::RecordingError& e) {
    EXPECT_EQ(std::string(e.what()), "line.plcrec: offset 8: a recording of a line of cells: open one of its cells "
                                     "(plc_cell monitor --recording line.plcrec --cell NAME)");
  }
}

}  // namespace
}  // namespace plc_cell
