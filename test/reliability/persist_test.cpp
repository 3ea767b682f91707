// Retentive persistence in-process: image format, slots, fallback on torn/corrupt files,
// and "a write that returned is on disk".
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>

#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/persist/crc32.h"
#include "plc_cell/persist/persister.h"
#include "plc_cell/persist/retentive_image.h"
#include "plc_cell/persist/slot_file.h"
#include "temp_dir.h"

using namespace plc_cell;
using namespace plc_cell::persist;

namespace {

Address at(const char* s) { return parse_address(s); }

std::unique_ptr<Plc> make_plc(const char* program = "ORG M1925\nOUT Y0\nEND\n") {
  auto plc = std::make_unique<Plc>();
  plc->locked([](ScanEngine& e, Memory&) {
    e.set_retentive({{Area::D, 0, 9}, {Area::M, 800, 809}, {Area::RC, 199, 201}});
    return 0;
  });
  plc->load_program_text(program, "t.il");
  return plc;
}

std::string read_file(const std::string& p) {
  std::ifstream f(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(f), {});
}
void write_file(const std::string& p, const std::string& data) {
  std::ofstream f(p, std::ios::binary | std::ios::trunc);
  f << data;
}

// The newest value of `a` in one store file, decoded as a fresh Plc would see it.
uint32_t stored_value(const std::string& file, const char* a) {
  std::vector<std::string> problems;
  auto slots = read_slots(file, &problems);
  EXPECT_FALSE(slots.empty()) << file;
  if (slots.empty()) return ~0u;
  const Slot* best = &slots[0];
  for (const auto& s : slots)
    if (s.seq > best->seq) best = &s;
  Memory m;
  decode_retentive(best->payload, {{Area::D, 0, 9}, {Area::M, 800, 809}, {Area::RC, 199, 201}}, &m);
  return m.read(at(a));
}

}  // namespace

TEST(Crc32, KnownValue) { EXPECT_EQ(crc32("123456789", 9), 0xCBF43926u); }

TEST(RetentiveImage, RoundTripsOnlyTheRanges) {
  Memory m;
  m.write(at("D3"), 42);
  m.write(at("D20"), 7);
  m.write(at("M805"), 1);
  m.write(at("RC201"), 0x12345678);
  m.set_disabled(Area::M, 805, true);
  std::vector<uint8_t> img;
  encode_retentive({{Area::D, 0, 9}, {Area::M, 800, 809}, {Area::RC, 199, 201}}, m, &img);
  Memory n;
  EXPECT_EQ(decode_retentive(img, {{Area::D, 0, 9}, {Area::M, 800, 809}, {Area::RC, 199, 201}}, &n), 23u);
  EXPECT_EQ(n.read(at("D3")), 42u);
  EXPECT_EQ(n.read(at("D20")), 0u);
  EXPECT_EQ(n.read(at("M805")), 1u);
  EXPECT_FALSE(n.disabled(Area::M, 805));  // the state is latched, a force flag is not
  EXPECT_EQ(n.read(at("RC201")), m.read(at("RC201")));
  EXPECT_NE(n.read(at("RC201")), 0u);
  // A narrower config restores the overlap only.
  Memory k;
  EXPECT_EQ(decode_retentive(img, {{Area::D, 2, 3}}, &k), 2u);
  EXPECT_EQ(k.read(at("D3")), 42u);
  img.resize(img.size() - 1);
  EXPECT_THROW(decode_retentive(img, {{Area::D, 0, 9}}, &k), Error);
}

TEST(Persister, RestoresRetentiveAfterRestartOnly) {
  TempDir dir;
  const PersistSettings s{dir.path() + "/store", 100000, true};
  {
    auto plc = make_plc();
    Persister p(*plc, s);
    plc->write(at("D3"), {42});
    plc->write(at("D50"), {9});  // not retentive
    plc->write(at("M801"), {1});
  }
  auto plc = make_plc();
  Persister p(*plc, s);
  EXPECT_EQ(plc->read(at("D3"), 1)[0], 42u);
  EXPECT_EQ(plc->read(at("D50"), 1)[0], 0u);
  EXPECT_EQ(plc->read(at("M801"), 1)[0], 1u);
  EXPECT_NE(p.status().restored.find("restored"), std::string::npos) << p.status().restored;
  EXPECT_TRUE(p.status().problems.empty());
}

TEST(Persister, AcknowledgedWriteIsInTheDurableFileWhenWriteReturns) {
  TempDir dir;
  // An interval of a minute: only the write's own flush can put it on disk in time.
  const PersistSettings s{dir.path() + "/store", 60000000, true};
  auto plc = make_plc();
  Persister p(*plc, s);
  for (uint32_t v = 1; v <= 20; ++v) {
    plc->write(at("D7"), {v});
    ASSERT_EQ(stored_value(s.file, "D7"), v);
  }
  plc->force(at("M809"), ForceAction::Set);
  EXPECT_EQ(stored_value(s.file, "M809"), 1u);
  const auto st = p.status();
  EXPECT_EQ(st.durable_seq, st.seq);
  EXPECT_TRUE(st.error.empty()) << st.error;
}

TEST(Persister, ProgramLatchedValuesReachTheLiveFileEveryScan) {
  TempDir dir;
  const PersistSettings s{dir.path() + "/store", 60000000, true};
  auto plc = make_plc("ORG M1925\nINC D=D5\nEND\n");
  Persister p(*plc, s);
  ASSERT_TRUE(plc->set_mode(RunMode::Run));
  for (uint64_t t = 1; t <= 30; ++t) {
    plc->scan(t * 1000);
    // Without any sync: what a kill -9 right now would leave behind.
    ASSERT_EQ(stored_value(s.file + ".live", "D5"), plc->read(at("D5"), 1)[0]);
  }
  EXPECT_EQ(plc->read(at("D5"), 1)[0], 30u);
}

// Two generations, then damage: the newest valid slot of the four wins, with a diagnostic.
class Damaged : public ::testing::Test {
 protected:
  void SetUp() override {
    s_ = {dir_.path() + "/store", 60000000, true};
    auto plc = make_plc();
    Persister p(*plc, s_);
    plc->write(at("D1"), {11});  // older generation
    old_main_ = read_file(s_.file);
    old_live_ = read_file(s_.file + ".live");
    plc->write(at("D1"), {22});  // newest
  }
  uint32_t restart_d1(PersistStatus* st) {
    auto plc = make_plc();
    Persister p(*plc, s_);
    *st = p.status();
    return plc->read(at("D1"), 1)[0];
  }
  TempDir dir_;
  PersistSettings s_;
  std::string old_main_, old_live_;
};

TEST_F(Damaged, CorruptNewestSlotsFallBackToPreviousGeneration) {
  // Flip one payload byte in the newest slot of both files: its CRC no longer matches.
  for (const std::string& f : {s_.file, s_.file + ".live"}) {
    std::string d = read_file(f);
    std::vector<std::string> pr;
    auto slots = read_slots(f, &pr);
    ASSERT_EQ(slots.size(), 2u);
    const int newest = slots[0].seq > slots[1].seq ? 0 : 1;
    const size_t off = (newest == 0 ? 0 : d.size() / 2) + 25;
    d[off] = char(d[off] ^ 0x40);
    write_file(f, d);
  }
  PersistStatus st;
  EXPECT_EQ(restart_d1(&st), 11u);
  ASSERT_EQ(st.problems.size(), 2u);
  EXPECT_NE(st.problems[0].find("CRC mismatch"), std::string::npos) << st.problems[0];
  EXPECT_NE(st.restored.find("fell back"), std::string::npos) << st.restored;
}

TEST_F(Damaged, TruncatedMainFileUsesLiveFile) {
  std::string d = read_file(s_.file);
  write_file(s_.file, d.substr(0, d.size() / 2 + 7));  // half a slot missing
  PersistStatus st;
  EXPECT_EQ(restart_d1(&st), 22u);
  EXPECT_FALSE(st.problems.empty());
}

TEST_F(Damaged, BothFilesTornUseWhateverSlotSurvived) {
  write_file(s_.file, std::string(3, 'x'));
  std::string d = read_file(s_.file + ".live");
  std::vector<std::string> pr;
  auto slots = read_slots(s_.file + ".live", &pr);
  ASSERT_EQ(slots.size(), 2u);
  const int newest = slots[0].seq > slots[1].seq ? 0 : 1;
  d[(newest == 0 ? 0 : d.size() / 2) + 30] ^= 1;
  write_file(s_.file + ".live", d);
  PersistStatus st;
  EXPECT_EQ(restart_d1(&st), 11u);
  EXPECT_GE(st.problems.size(), 2u);
}

TEST_F(Damaged, NothingValidStartsClearedAndSaysSo) {
  write_file(s_.file, "garbage");
  write_file(s_.file + ".live", "");
  PersistStatus st;
  EXPECT_EQ(restart_d1(&st), 0u);
  EXPECT_NE(st.restored.find("no stored image"), std::string::npos) << st.restored;
}

// A slot whose CRC is valid but whose content is not a whole image (a writer bug, a store
// from a broken build): it is checked whole first, so none of it reaches memory, and the
// log says what was restored and from where, or "nothing restored" and why.
class ChecksummedButDamaged : public ::testing::Test {
 protected:
  const std::vector<AreaRange> ranges_{{Area::D, 0, 9}, {Area::M, 800, 809}, {Area::RC, 199, 201}};
  std::vector<uint8_t> image_with_d1(uint16_t v) {
    Memory m;
    m.write(at("D1"), v);
    m.write(at("M803"), 1);
    std::vector<uint8_t> img;
    encode_retentive(ranges_, m, &img);
    return img;
  }
  // Restarts on the store as it is; returns D1 and M803 and the log lines.
  std::pair<uint32_t, uint32_t> restart(std::vector<std::string>* log, PersistStatus* st) {
    auto plc = make_plc();
    Persister p(*plc, s_, [log](const std::string& l) { log->push_back(l); });
    *st = p.status();
    return {plc->read(at("D1"), 1)[0], plc->read(at("M803"), 1)[0]};
  }
  TempDir dir_;
  PersistSettings s_{dir_.path() + "/store", 60000000, true};
};

TEST_F(ChecksummedButDamaged, ImageIsCheckedWholeBeforeAnyWrite) {
  std::vector<uint8_t> img = image_with_d1(99);
  // A fourth range whose bounds do not fit: D5-D3.
  const uint8_t bad[9] = {uint8_t(Area::D), 5, 0, 0, 0, 3, 0, 0, 0};
  img.insert(img.end(), bad, bad + 9);
  Memory m;
  EXPECT_THROW(decode_retentive(img, ranges_, &m), Error);
  EXPECT_EQ(m.read(at("D1")), 0u);  // the good ranges before the bad one were not written
  EXPECT_EQ(m.read(at("M803")), 0u);
  EXPECT_THROW(parse_retentive(img), Error);
}

TEST_F(ChecksummedButDamaged, BadRangeHeaderRestoresNothingAndSaysSo) {
  std::vector<uint8_t> img = image_with_d1(99);
  const uint8_t bad[9] = {uint8_t(Area::D), 5, 0, 0, 0, 3, 0, 0, 0};
  img.insert(img.end(), bad, bad + 9);
  { SlotFile f(s_.file, 100, img); }  // the only store, CRC valid
  std::vector<std::string> log;
  PersistStatus st;
  const auto v = restart(&log, &st);
  EXPECT_EQ(v.first, 0u);
  EXPECT_EQ(v.second, 0u);
  ASSERT_EQ(st.problems.size(), 1u);
  EXPECT_NE(st.problems[0].find("slot 0"), std::string::npos) << st.problems[0];
  EXPECT_NE(st.problems[0].find("bad range D5-D3"), std::string::npos) << st.problems[0];
  EXPECT_EQ(st.restored.rfind("nothing restored: ", 0), 0u) << st.restored;
  // The problem first, then the one line that says what memory holds.
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[0], "persist: " + st.problems[0]);
  EXPECT_EQ(log[1], "persist: " + st.restored);
}

TEST_F(ChecksummedButDamaged, ElementCountDisagreeingFallsBackToOlderSlotOnly) {
  const std::vector<uint8_t> good = image_with_d1(11);
  std::vector<uint8_t> shorter = image_with_d1(77);
  // The last range (RC199-RC201, 10 bytes of values) now announces RC199-RC205: more values
  // than the slot holds. Same size, so the slot is a valid one of this file.
  shorter[shorter.size() - 10 - 4] = 205;
  {
    SlotFile f(s_.file, 5, good);
    f.write(6, shorter, true);  // newer slot (slot 1), valid CRC over the short image
  }
  std::vector<std::string> log;
  PersistStatus st;
  const auto v = restart(&log, &st);
  EXPECT_EQ(v.first, 11u);  // from the older slot, nothing of the newer one
  EXPECT_EQ(v.second, 1u);
  ASSERT_EQ(st.problems.size(), 1u);
  EXPECT_NE(st.problems[0].find("slot 1"), std::string::npos) << st.problems[0];
  EXPECT_NE(st.problems[0].find("present"), std::string::npos) << st.problems[0];
  EXPECT_NE(st.restored.find("restored 23 retentive elements (D0-D9,M800-M809,RC199-RC201) from " + s_.file +
                             " slot 0 (sequence 5)"),
            std::string::npos)
      << st.restored;
  EXPECT_NE(st.restored.find("fell back past 1 damaged slot(s)"), std::string::npos) << st.restored;
  ASSERT_EQ(log.size(), 2u);
  EXPECT_EQ(log[1], "persist: " + st.restored);
}

TEST_F(ChecksummedButDamaged, NarrowerConfigSaysWhichRangesCameBack) {
  { SlotFile f(s_.file, 3, image_with_d1(42)); }
  auto plc = std::make_unique<Plc>();
  plc->locked([](ScanEngine& e, Memory&) {
    e.set_retentive({{Area::D, 1, 2}, {Area::R, 0, 9}});  // R was never stored
    return 0;
  });
  plc->load_program_text("ORG M1925\nOUT Y0\nEND\n", "t.il");
  Persister p(*plc, s_);
  EXPECT_EQ(plc->read(at("D1"), 1)[0], 42u);
  EXPECT_NE(p.status().restored.find("restored 2 retentive elements (D1-D2) from"), std::string::npos)
      << p.status().restored;
}

TEST_F(Damaged, TruncationBehindAnIntactFirstSlotIsNamed) {
  std::string d = read_file(s_.file);
  write_file(s_.file, d.substr(0, d.size() / 2 + 7));  // slot 0 whole, slot 1 mostly gone
  std::vector<std::string> pr;
  read_slots(s_.file, &pr);
  ASSERT_FALSE(pr.empty());
  EXPECT_NE(pr[0].find("two slots of"), std::string::npos) << pr[0];
  EXPECT_NE(pr[0].find("truncated"), std::string::npos) << pr[0];
}
