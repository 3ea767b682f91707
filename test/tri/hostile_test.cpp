// Hostile input, generated: thousands of mutated and random frames (a fixed seed, a
// bounded count). The slave never crashes, every reply is a whole frame or the Ctrl-E
// echo, and a request that is refused (error, framing error, silence) changes nothing.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "../fatek/fatek_link.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/serial_port.h"
#include "plc_cell/tri/server.h"
#include "plc_cell/tri/slave.h"

using namespace plc_cell;
using namespace plc_cell::tri;

namespace {

// Every area the host link can reach, as raw storage.
struct Image {
  std::vector<std::vector<uint8_t>> bits;
  std::vector<std::vector<uint16_t>> words;
  bool operator==(const Image& o) const { return bits == o.bits && words == o.words; }
};

Image snapshot(Plc& plc) {
  return plc.locked([](ScanEngine&, Memory& m) {
    Image im;
    for (Area a : {Area::X, Area::Y, Area::M, Area::T, Area::C})
      im.bits.emplace_back(m.bits(a), m.bits(a) + area_size(a));
    for (Area a : {Area::RT, Area::RC, Area::R, Area::D, Area::F})
      im.words.emplace_back(m.words(a), m.words(a) + Memory::word_count(a));
    return im;
  });
}

const char* kValid[] = {"IR", "IW01", "RI00", "RO1F", "RR3F", "RT07", "RC00", "RM00", "Rm3F", "RU01", "Ru02",
                        "RVIK", "RV$A", "RVD0E10", "RVS0902", "RVH2", "WI0012", "WO01FF", "WR3F00", "WT0701",
                        "WC0080", "WM009999", "Wm010000", "WU020001", "Wu031234", "WVIA80000000", "WV$Btext",
                        "WVD03E804D2", "WVS0801000E", "WVH100000001", "RA0204", "WA01020001FFFF", "RXI00640A",
                        "RX$000A", "WXI0001010001", "WX$000CHello TRi", "wb0100FF", "Wb010000", "C3"};

std::string mutate(std::mt19937& rng, std::string s) {
  std::uniform_int_distribution<int> byte(0, 255), op(0, 5);
  const int n = 1 + int(rng() % 3);
  for (int k = 0; k < n && !s.empty(); ++k) {
    const size_t at = rng() % s.size();
    switch (op(rng)) {
      case 0: s[at] = char(byte(rng)); break;                       // any byte
      case 1: s[at] = "0123456789ABCDEF*@\r\x05"[rng() % 20]; break; // a plausible one
      case 2: s.erase(at, 1); break;
      case 3: s.insert(at, 1, char(byte(rng))); break;
      case 4: s.resize(at); break;                                  // cut short
      case 5: s.insert(at, s.substr(0, rng() % s.size())); break;   // repeated piece
    }
  }
  return s;
}

std::string frame_of(std::mt19937& rng, const std::string& body) {
  Frame f;
  f.body = body;
  f.multipoint = rng() % 2;
  f.id = rng() % 4 == 0 ? int(rng() % 256) : 1;
  return encode_frame(f);
}

// True when every frame of the reply is an error (ER..) or a framing error (FE).
bool only_refusals(const std::string& reply) {
  bool refused = true;
  Decoder d;
  d.feed(reply, [&](const Decoder::Event& e) {
    if (e.kind == Decoder::Event::FrameReady && e.frame.body.rfind("ER", 0) != 0 && e.frame.body != "FE")
      refused = false;
  });
  return refused;
}

}  // namespace

TEST(TriHostile, MutatedAndRandomFramesNeverCrashAndRefusalsChangeNothing) {
  Plc plc;
  plc.load_program_text("ORG X0\nOUT Y0\nEND\n", "t.il");
  Slave slave(plc, 1);
  std::mt19937 rng(20261125);
  int refused = 0, answered = 0, silent = 0;
  for (int i = 0; i < 6000; ++i) {
    std::string bytes;
    if (i % 10 == 9) {  // pure noise
      bytes.resize(rng() % 64);
      for (char& c : bytes) c = char(rng());
    } else {
      bytes = frame_of(rng, kValid[rng() % (sizeof kValid / sizeof *kValid)]);
      if (i % 3) bytes = mutate(rng, bytes);  // a third go whole: the frames around them are hostile
    }
    if (slave.id() != 1) slave.answer("IW01*\r");  // a mutated IW moved the ID
    const Image before = snapshot(plc);
    const std::string reply = slave.answer(bytes);
    ASSERT_TRUE(reply.empty() || reply.back() == '\r' || reply.back() == kEnq) << i;
    ASSERT_LE(reply.size(), 16 * (bytes.size() + 1) + 256) << i;
    if (only_refusals(reply)) {
      ASSERT_TRUE(snapshot(plc) == before) << "refused request " << i << " changed memory";
      (reply.empty() ? silent : refused)++;
    } else {
      ++answered;
    }
  }
  // The generator reaches every outcome.
  EXPECT_GT(refused, 500);
  EXPECT_GT(answered, 500);
  EXPECT_GT(silent, 500);
}

TEST(TriHostile, TcpServerSurvivesAndStillAnswers) {
  Plc plc;
  ServerOptions o;
  o.frame_timeout_ms = 200;
  o.max_connections = 64;  // the 20 clients below may not all be reaped when the last one comes
  TcpServer server(plc, "127.0.0.1", 0, o);
  server.start();
  std::mt19937 rng(7);
  for (int round = 0; round < 20; ++round) {
    const int fd = fatek_test::connect_local(server.port());
    for (int i = 0; i < 100; ++i) {
      std::string bytes = mutate(rng, frame_of(rng, kValid[rng() % (sizeof kValid / sizeof *kValid)]));
      if (::send(fd, bytes.data(), bytes.size(), MSG_NOSIGNAL) < 0) break;
    }
    ::close(fd);
  }
  const int fd = fatek_test::connect_local(server.port());
  const std::string ir = "\rIR*\r";  // the CR ends whatever a previous client left
  ASSERT_EQ(::send(fd, ir.data(), ir.size(), MSG_NOSIGNAL), ssize_t(ir.size()));
  std::string got;
  char buf[64];
  // A mutated IW may have given the server another ID: any IR reply will do.
  while ((got.empty() || got.back() != '\r') && fatek::wait_readable(fd, 3000)) {
    const ssize_t n = ::recv(fd, buf, sizeof buf, 0);
    if (n <= 0) break;
    got.append(buf, size_t(n));
  }
  EXPECT_EQ(got.substr(0, 2), "IR") << got;
  EXPECT_EQ(got.size(), 6u) << got;
  EXPECT_TRUE(server.status().running);
  ::close(fd);
  server.stop();
}
