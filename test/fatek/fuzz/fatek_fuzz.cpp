// Randomized / mutated-frame test of the codec, built with ASan+UBSan (cmake/subsystems/fatek.cmake).
// 1,000,000+ frames: spec vectors mutated (bit flips, insertions, deletions, truncation,
// stray STX/ETX, garbage), half of them with the LRC repaired so the command parsers are
// reached too. The decoder must never crash, never hold more than one frame, and every
// frame it reports must be well-formed; the parsers must never crash on any of them.
#include <gtest/gtest.h>

#include <random>

#include "plc_cell/fatek/protocol.h"

using namespace plc_cell;
using namespace plc_cell::fatek;

namespace {

const char* kSeeds[] = {
    "0140", "01400290000", "01411", "01410", "014210016", "0142" "2X0016", "01423Y0005", "01424Y0005",
    "014307Y0010", "014301010001", "014406X0050", "014400M0000", "014504Y00001001",
    "014603R00012", "014601" "0A57FC40001", "014602DR00000", "014702WY0008AAAA5555", "014701DR0010000012345",
    "014803R00001Y0009DWM0000", "0148" "05C341003547BA", "014904Y00001Y00010WY00085555DF00002000000FF",
    "014EABCDEFG", "0153", "01530210102408000010001000064006407D203E800001F8810000100" "0100",
    "014620R00000", "0146" "20DD00000", "014700R00000", "00450" "1Y00001",
};

std::string with_frame(const std::string& body) {
  std::string s = "\x02" + body;
  std::string out = s;
  append_hex(out, lrc(s), 2);
  out.push_back('\x03');
  return out;
}

}  // namespace

TEST(FatekFuzz, MillionMutatedFramesUnderSanitizers) {
  std::mt19937 rng(12345);
  auto rnd = [&](uint32_t n) { return uint32_t(rng() % n); };
  std::vector<std::string> seeds;
  for (const char* s : kSeeds) seeds.push_back(with_frame(s));
  // Long frames too: a 64-word write and a 256-char loop-back.
  seeds.push_back(with_frame("014740R00000" + std::string(256, 'F')));
  seeds.push_back(with_frame("014E" + std::string(256, 'Z')));

  Decoder dec, ref, bulk;
  std::vector<uint64_t> bulk_frames;
  bulk_frames.reserve(64);
  auto fnv = [](const std::string& d) {
    uint64_t h = 1469598103934665603ull ^ d.size();
    for (unsigned char c : d) h = (h ^ c) * 1099511628211ull;
    return h;
  };
  uint64_t frames = 0, good = 0, parsed_ok = 0, errors = 0;
  std::string stream;
  const uint64_t kFrames = 1000000;
  for (uint64_t i = 0; i < kFrames; ++i) {
    std::string f = seeds[rnd(uint32_t(seeds.size()))];
    const int kind = int(rnd(10));
    const int edits = 1 + int(rnd(4));
    for (int e = 0; e < edits && kind != 0; ++e) {
      const size_t pos = rnd(uint32_t(f.size()) + 1);
      switch (rnd(7)) {
        case 0: if (pos < f.size()) f[pos] ^= char(1u << rnd(8)); break;
        case 1: f.insert(pos, 1, char(rnd(256))); break;
        case 2: if (pos < f.size()) f.erase(pos, 1); break;
        case 3: f.resize(pos); break;  // cut short
        case 4: f.insert(pos, 1, rnd(2) ? '\x02' : '\x03'); break;
        case 5: f.insert(pos, std::string(rnd(600), char(0x20 + rnd(95)))); break;  // oversize
        case 6: if (pos < f.size()) f[pos] = "0123456789ABCDEFXYMRDWabz"[rnd(25)]; break;
      }
    }
    if (kind >= 5 && f.size() >= 4 && f[0] == '\x02' && f.back() == '\x03') {
      // Repair the LRC so that the mutated data reaches the command parsers.
      std::string body = f.substr(0, f.size() - 3);
      f = body;
      append_hex(f, lrc(body), 2);
      f.push_back('\x03');
    }
    if (rnd(8) == 0) f.insert(0, std::string(rnd(20), char(rnd(256))));  // line noise before STX
    ++frames;
    // The bulk feed() path must see exactly what byte-wise push() sees.
    bulk_frames.clear();
    size_t bulk_errors = 0;
    bulk.feed(reinterpret_cast<const uint8_t*>(f.data()), f.size(),
              [&](const Frame& fr) { bulk_frames.push_back(fnv(fr.data)); }, [&](Decoder::Fault) { ++bulk_errors; });
    size_t byte_frames = 0, byte_errors = 0;
    for (char c : f) {
      const auto st0 = ref.push(uint8_t(c));
      if (st0 == Decoder::Status::Error) ++byte_errors;
      if (st0 == Decoder::Status::Frame) {
        ASSERT_LT(byte_frames, bulk_frames.size());
        ASSERT_EQ(fnv(ref.frame().data), bulk_frames[byte_frames]);
        ++byte_frames;
      }
    }
    ASSERT_EQ(byte_frames, bulk_frames.size());
    ASSERT_EQ(byte_errors, bulk_errors);
    for (char c : f) {
      const auto st = dec.push(uint8_t(c));
      if (st == Decoder::Status::Error) {
        ++errors;
        continue;
      }
      if (st != Decoder::Status::Frame) continue;
      ++good;
      const Frame& fr = dec.frame();
      ASSERT_LE(fr.data.size(), kMaxData);
      ASSERT_LE(fr.data.capacity(), 4 * kMaxData);  // bounded: no growth beyond a frame
      // A reported frame re-encodes to a frame that decodes to the same content.
      Decoder d2;
      Frame copy = fr;
      const std::string again = encode_frame(copy);
      Decoder::Status s2 = Decoder::Status::Incomplete;
      for (char c2 : again) s2 = d2.push(uint8_t(c2));
      ASSERT_EQ(s2, Decoder::Status::Frame);
      ASSERT_EQ(d2.frame().data, fr.data);
      // Slave side: any frame parses to Ok or an error code, and an Ok request re-encodes.
      Request req;
      if (parse_request(fr, &req) == ErrorCode::Ok) {
        ++parsed_ok;
        Response rsp;
        rsp.station = fr.station;
        if (req.cmd == Cmd::ReadRegisters || req.cmd == Cmd::ReadDiscretes || req.cmd == Cmd::ReadEnable)
          rsp.values.assign(req.count, 1);
        if (req.cmd == Cmd::MixedRead) rsp.values.assign(req.points.size(), 1);
        rsp.text = req.text;
        const std::string out = encode_response(req, rsp);
        ASSERT_LE(out.size(), kMaxFrame);
        // Master side: the response parses against the request.
        Decoder d3;
        for (char c3 : out) d3.push(uint8_t(c3));
        Response back;
        std::string why;
        if (req.station != 0 && req.cmd != Cmd::GistStatus && req.cmd != Cmd::DetailedStatus) {
          ASSERT_TRUE(parse_response(req, d3.frame(), &back, &why)) << why;
        }
      }
      // Master side on arbitrary frames: must not crash.
      Request any;
      any.station = fr.station;
      any.cmd = Cmd(fr.command);
      any.start = parse_address("R0");
      any.count = 3;
      Response r2;
      std::string why;
      (void)parse_response(any, fr, &r2, &why);
    }
  }
  dec.timeout();
  EXPECT_EQ(frames, kFrames);
  EXPECT_GT(good, kFrames / 10);        // the mutations leave many frames intact
  EXPECT_GT(parsed_ok, kFrames / 20);   // and the command parsers saw plenty of them
  EXPECT_GT(errors, kFrames / 4);       // while the decoder rejected many others
}

TEST(FatekFuzz, DecoderRejectsAndResyncs) {
  Decoder d;
  std::vector<std::string> faults;
  std::vector<std::string> frames;
  auto feed = [&](const std::string& s) {
    d.feed(reinterpret_cast<const uint8_t*>(s.data()), s.size(), [&](const Frame& f) { frames.push_back(f.data); },
           [&](Decoder::Fault f) { faults.push_back(fault_name(f)); });
  };
  feed("garbage\x01\xff");
  EXPECT_TRUE(faults.empty());
  feed(std::string("\x02") + "014EAB" + "00\x03");  // bad LRC
  ASSERT_EQ(faults.size(), 1u);
  EXPECT_EQ(faults[0], "bad LRC");
  feed(std::string("\x02") + "01Z0C7\x03");  // non-hex command
  EXPECT_EQ(faults.back(), "non-hex station, command or LRC");
  feed(std::string("\x02") + std::string(600, 'A') + "\x03");  // oversize
  EXPECT_EQ(faults.back(), "frame longer than 508 bytes");
  feed(std::string("\x02") + "0140");  // cut short, then a good frame resyncs
  feed(with_frame("0140"));
  EXPECT_EQ(faults.back(), "frame cut short");
  ASSERT_EQ(frames.size(), 1u);
  feed(std::string("\x02") + "01");
  EXPECT_TRUE(d.timeout());
  EXPECT_FALSE(d.in_frame());
  feed(with_frame("014" "EHI"));
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_EQ(frames[1], "HI");
  // Exactly 500 data chars is legal, 501 is not.
  feed(with_frame("014E" + std::string(500, 'Q')));
  EXPECT_EQ(frames.size(), 3u);
  feed(with_frame("014E" + std::string(501, 'Q')));
  EXPECT_EQ(frames.size(), 3u);
  EXPECT_EQ(faults.back(), "frame longer than 508 bytes");
}
