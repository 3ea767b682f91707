// Damaged, cut-short and foreign files: a clear error naming the file, the offset and why,
// and never a crash.
#include <gtest/gtest.h>

#include <random>

#include "helpers.h"
#include "plc_cell/recording/envelope.h"
#include "plc_cell/recording/reader.h"

namespace plc_cell {
namespace {

// The error of reading bytes, or "" when they read.
std::string error_of(const std::string& bytes) {
  try {
    recording::Reader::parse(bytes, "bad.plcrec");
  } catch (const recording::RecordingError& e) {
    return e.what();
  }
  return "";
}

class CorruptFile : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    bytes_ = new std::string(testing::file_bytes(testing::record_conveyor(testing::scratch_dir("corrupt"), "20ms")));
  }
  static void TearDownTestSuite() { delete bytes_; }
  static std::string* bytes_;
};
std::string* CorruptFile::bytes_ = nullptr;

TEST_F(CorruptFile, TheWholeFileReads) {
  ASSERT_GT(bytes_->size(), 100u);
  EXPECT_EQ(error_of(*bytes_), "");
  EXPECT_EQ(recording::Reader::parse(*bytes_, "x").scans(), 20u);
}

TEST_F(CorruptFile, EveryTruncationIsRefusedWithItsOffset) {
  for (size_t n = 0; n < bytes_->size(); ++n) {
    const std::string e = error_of(bytes_->substr(0, n));
    ASSERT_EQ(e.rfind("bad.plcrec: offset ", 0), 0u) << "cut at " << n << ": '" << e << "'";
  }
  EXPECT_EQ(error_of(bytes_->substr(0, 3)), "bad.plcrec: offset 0: not a plc_cell recording (no PLCREC magic)");
  EXPECT_NE(error_of(bytes_->substr(0, bytes_->size() - 1)).find("file cut short"), std::string::npos);
  EXPECT_NE(error_of(*bytes_ + "x").find("bad.plcrec: offset 22: packed size"), std::string::npos);
}

TEST_F(CorruptFile, ForeignFilesAndOtherVersions) {
  EXPECT_EQ(error_of("PK\x03\x04 a zip file, not a recording"),
            "bad.plcrec: offset 0: not a plc_cell recording (no PLCREC magic)");
  std::string v3 = *bytes_;
  v3[8] = 3;
  EXPECT_EQ(error_of(v3), "bad.plcrec: offset 8: format version 3, this plc_cell reads versions 1 and 2");
  std::string v2 = *bytes_;  // a line's recording (line_recording.h): a cell's reader says what it is
  v2[8] = 2;
  EXPECT_EQ(error_of(v2), "bad.plcrec: offset 8: a recording of a line of cells: open one of its cells "
                          "(plc_cell monitor --recording bad.plcrec --cell NAME)");
  std::string huge = *bytes_;
  huge[17] = '\x7f';  // the payload's size: far more than the packed bytes can give
  EXPECT_NE(error_of(huge).find("bad.plcrec: offset 10: payload size"), std::string::npos) << error_of(huge);
}

TEST_F(CorruptFile, RandomByteFlipsAreRefusedOrRead) {
  std::mt19937 rng(7);
  for (int k = 0; k < 3000; ++k) {
    std::string b = *bytes_;
    const int flips = 1 + int(rng() % 4);
    for (int f = 0; f < flips; ++f) b[rng() % b.size()] ^= char(1 + rng() % 255);
    const std::string e = error_of(b);
    if (e.empty()) continue;
    ASSERT_EQ(e.rfind("bad.plcrec: offset ", 0), 0u) << e;
  }
}

// The envelope's CRC catches flips in the packed data; the payload's own checks are
// exercised by damaged payloads in a sound envelope.
TEST_F(CorruptFile, DamagedPayloadsInASoundEnvelope) {
  const std::string payload = recording::unpack(*bytes_, "x");
  EXPECT_EQ(error_of(recording::pack(payload)), "");
  for (size_t n = 0; n < payload.size(); n += (n < 200 || payload.size() - n < 200) ? 1 : 97) {
    const std::string e = error_of(recording::pack(payload.substr(0, n)));
    ASSERT_EQ(e.rfind("bad.plcrec: offset ", 0), 0u) << "payload cut at " << n << ": '" << e << "'";
    EXPECT_NE(e.find("of the unpacked data"), std::string::npos) << e;
  }
  std::mt19937 rng(11);
  size_t refused = 0;
  for (int k = 0; k < 1000; ++k) {
    std::string p = payload;
    const int flips = 1 + int(rng() % 3);
    for (int f = 0; f < flips; ++f) p[rng() % p.size()] ^= char(1 + rng() % 255);
    const std::string e = error_of(recording::pack(p));
    if (e.empty()) continue;
    ++refused;
    ASSERT_EQ(e.rfind("bad.plcrec: offset ", 0), 0u) << e;
  }
  EXPECT_GT(refused, 0u);
  std::string extra = payload + "zz";
  EXPECT_NE(error_of(recording::pack(extra)).find("2 bytes after the last scan"), std::string::npos);
}

}  // namespace
}  // namespace plc_cell
