// A real PLC as the monitor's source, with the soft PLC's own FATEK server standing in for
// it on loopback TCP: values read back, the polls coalesced (frames counted on the server),
// writes and forcing through the protocol's commands, a refused write, and a link that drops.
#include <gtest/gtest.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/fatek/server.h"
#include "plc_cell/remote/fatek_link.h"
#include "remote_fixture.h"

namespace plc_cell {
namespace {

using remote_test::error_of;

class FatekSource : public ::testing::Test {
 protected:
  FatekSource() {
    plc.load_program_file(remote_test::kConveyorIl);
    serve(0);
    source = remote_test::conveyor_source<remote::FatekLink>(
        remote_test::on_loopback<remote::FatekLinkOptions>(server->port(), 500), std::chrono::milliseconds(0));
  }
  void serve(int port, const std::string& writable = "D0-D99,Y0-Y15") {
    fatek::TcpServerOptions o;
    o.port = port;
    if (!writable.empty()) o.writable = WritableRanges::parse(writable);
    server = std::make_unique<fatek::TcpServer>(plc, o);
    server->start();
  }
  Plc plc{SoftCell::functions()};
  std::unique_ptr<fatek::TcpServer> server;
  std::unique_ptr<remote::RemoteSource> source;
};

TEST_F(FatekSource, ReadsWhatThePlcHasInFewFrames) {
  std::vector<Address> addrs;
  std::vector<uint32_t> expected;
  for (uint32_t i = 0; i < 10; ++i) {
    plc.write(Address{Area::D, Width::Word, i}, {1000 + i});
    addrs.push_back(Address{Area::D, Width::Word, i});
    expected.push_back(1000 + i);
  }
  for (uint32_t i = 0; i < 8; ++i) {
    plc.write(Address{Area::Y, Width::Bit, i}, {i % 2});
    addrs.push_back(Address{Area::Y, Width::Bit, i});
    expected.push_back(i % 2);
  }
  plc.write(parse_address("DR200"), {70000});
  addrs.push_back(parse_address("DR200"));
  expected.push_back(70000);
  plc.write(parse_address("M100"), {1});
  addrs.push_back(parse_address("M100"));
  expected.push_back(1);

  // The first poll also reads the forced points of the program's discretes with 43, a frame
  // per run of one area: X0-X4, Y0-Y2, M0, M1924-M1925, T50-T51.
  EXPECT_TRUE(source->read({}).values.empty());
  EXPECT_EQ(server->status().requests, 1u + 5u);
  const uint64_t before = server->status().requests;
  const monitor::Frame f = source->read(addrs);
  EXPECT_EQ(f.values, expected);
  EXPECT_EQ(f.mode, RunMode::Stop);
  const uint64_t frames = server->status().requests - before;
  // 20 addresses: the status frame and one 48 mixed read (weight 10 + 8 + 2 + 1 <= 64), and
  // the forced points of the discretes new to it: Y0-Y7 (Y0-Y2 read through), M100.
  EXPECT_EQ(frames, 2u + 2u);
  EXPECT_EQ(source->frames(), server->status().requests);
  const monitor::CellStatus s = source->status();
  EXPECT_EQ(s.note, "power flow computed from polled values");
  ASSERT_EQ(s.servers.size(), 1u);
  EXPECT_TRUE(s.servers[0].second.link_up);
  EXPECT_EQ(s.servers[0].second.requests, 1u + 5u + 4u);
  EXPECT_EQ(s.scan_note, remote::kRemoteScanNote);  // the PLC's scan is not known over its host link
  EXPECT_EQ(s.scan.cycle.count, 0u);               // and the polls' time is not given as it
  ASSERT_EQ(s.extensions.size(), 1u);
  EXPECT_EQ(s.extensions[0].name, "polling");
  EXPECT_EQ(s.extensions[0].values[0], (std::pair<std::string, std::string>{"polls", "2"}));
  EXPECT_TRUE(s.mode_switchable);
  EXPECT_EQ(source->program()->file, "conveyor.il");
  EXPECT_FALSE(source->program()->program.code.empty());

  // 100 registers and 32 discretes: status, a 46 block of D0-D63, a 44 block of Y0-Y31
  // joined to the rest of D in mixed frames: a handful, not 132 (and one 43 frame for the
  // forced points of Y8-Y31).
  std::vector<Address> many;
  for (uint32_t i = 0; i < 100; ++i) many.push_back(Address{Area::D, Width::Word, i});
  for (uint32_t i = 0; i < 32; ++i) many.push_back(Address{Area::Y, Width::Bit, i});
  const uint64_t at = server->status().requests;
  EXPECT_EQ(source->read(many).values.size(), 132u);
  EXPECT_LE(server->status().requests - at, 4u + 1u);
  EXPECT_EQ(source->frames(), server->status().requests);
}

TEST_F(FatekSource, WritesForcesAndRunStopGoThroughTheProtocol) {
  source->write(parse_address("D20"), {1234, 5678});
  EXPECT_EQ(plc.read(parse_address("D20"), 2), (std::vector<uint32_t>{1234, 5678}));
  source->force(parse_address("Y5"), ForceAction::Disable);
  source->force(parse_address("Y5"), ForceAction::Set);
  EXPECT_TRUE(plc.locked([](ScanEngine&, Memory& m) { return m.disabled(Area::Y, 5) && m.bit(Area::Y, 5); }));
  // This PLC takes writes to D0-D99 and Y0-Y15 only: RUN/STOP is refused (FATEK error 4).
  EXPECT_NE(error_of([&] { source->set_mode(RunMode::Run); }).find("to command 41"), std::string::npos);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
  const int port = server->port();
  server.reset();
  serve(port, "");  // everything writable
  source->set_mode(RunMode::Run);
  EXPECT_EQ(plc.mode(), RunMode::Run);
  EXPECT_EQ(source->read({}).mode, RunMode::Run);
  source->set_mode(RunMode::Stop);
  EXPECT_EQ(plc.mode(), RunMode::Stop);
}

TEST_F(FatekSource, AWriteThePlcRefusesChangesNothingAndTheLinkStaysUp) {
  const std::string e = error_of([&] { source->write(parse_address("D500"), {9}); });
  EXPECT_NE(e.find("FATEK"), std::string::npos) << e;
  EXPECT_NE(e.find("write"), std::string::npos) << e;
  EXPECT_EQ(plc.read(parse_address("D500"), 1), std::vector<uint32_t>{0});
  const monitor::CellStatus s = source->status();
  EXPECT_TRUE(s.servers[0].second.link_up);
  EXPECT_NE(s.servers[0].second.last_error.find("write"), std::string::npos);
  EXPECT_EQ(error_of([&] { source->force(parse_address("D5"), ForceAction::Set); }),
            "D5: only a single discrete is forced");
}

TEST_F(FatekSource, ALinkThatDropsIsReportedAndComesBack) {
  ASSERT_EQ(source->read({parse_address("D0")}).values.size(), 1u);
  const int port = server->port();
  server.reset();  // the PLC goes away
  const std::string e = error_of([&] { source->read({parse_address("D0")}); });
  EXPECT_NE(e.find("link down"), std::string::npos) << e;
  monitor::CellStatus s = source->status();
  EXPECT_FALSE(s.servers[0].second.link_up);
  EXPECT_NE(s.servers[0].second.last_error.find("read"), std::string::npos);
  EXPECT_EQ(s.servers[0].second.rejected, 1u);
  EXPECT_FALSE(s.mode_known);  // not the mode it last reported
  serve(port);  // it comes back on its address
  plc.write(parse_address("D0"), {42});
  EXPECT_EQ(source->read({parse_address("D0")}).values, std::vector<uint32_t>{42});
  s = source->status();
  EXPECT_TRUE(s.servers[0].second.link_up);
  EXPECT_TRUE(s.mode_known);
  EXPECT_EQ(s.servers[0].second.last_error, "");  // the old error is not shown as the link's now
  EXPECT_EQ(s.servers[0].second.rejected, 1u);     // it is counted
}

TEST_F(FatekSource, ForcedPointsAreReadFromThePlc) {
  plc.force(parse_address("X3"), ForceAction::Disable);  // in the PLC, not through the source
  plc.force(parse_address("M100"), ForceAction::Disable);
  const monitor::Frame f = source->read({parse_address("X3"), parse_address("X4"), parse_address("M100"),
                                         parse_address("D0"), parse_address("WX0")});
  EXPECT_EQ(f.forced, (std::vector<uint8_t>{1, 0, 1, 0, 0}));
  monitor::CellStatus s = source->status();
  EXPECT_EQ(s.forced, (std::vector<Address>{parse_address("X3"), parse_address("M100")}));
  EXPECT_NE(s.forced_note.find("read from the PLC"), std::string::npos) << s.forced_note;
  // Forced and released through the source: known at once.
  source->force(parse_address("Y5"), ForceAction::Disable);
  EXPECT_EQ(source->status().forced,
            (std::vector<Address>{parse_address("X3"), parse_address("Y5"), parse_address("M100")}));
  source->force(parse_address("Y5"), ForceAction::Enable);
  EXPECT_EQ(source->status().forced, (std::vector<Address>{parse_address("X3"), parse_address("M100")}));
}

TEST_F(FatekSource, ForcedPointsAreReadAgainOnceTheirTimeHasCome) {
  source = remote_test::conveyor_source<remote::FatekLink>(
      remote_test::on_loopback<remote::FatekLinkOptions>(server->port(), 500), std::chrono::milliseconds(0),
      std::chrono::milliseconds(0));  // every poll
  source->read({parse_address("X3")});
  EXPECT_TRUE(source->status().forced.empty());
  plc.force(parse_address("X3"), ForceAction::Disable);
  EXPECT_EQ(source->read({parse_address("X3")}).forced, std::vector<uint8_t>{1});
  EXPECT_EQ(source->status().forced, std::vector<Address>{parse_address("X3")});
}

TEST(FatekSourceDown, WithinTheRetryIntervalADownLinkFailsAtOnce) {
  // Nothing listens on port 1.
  const auto source = remote_test::conveyor_source<remote::FatekLink>(
      remote_test::on_loopback<remote::FatekLinkOptions>(1, 300), std::chrono::hours(1));
  EXPECT_NE(error_of([&] { source->read({parse_address("D0")}); }).find("link down"), std::string::npos);
  const uint64_t frames = source->frames();
  // Refused without touching the line.
  EXPECT_NE(error_of([&] { source->read({parse_address("D0")}); }).find("link down"), std::string::npos);
  EXPECT_EQ(source->frames(), frames);
  EXPECT_EQ(source->status().servers[0].second.rejected, 1u);
}

TEST(RemoteProgram, AProgramThatDoesNotParseNamesItsLine) {
  EXPECT_THROW(remote::load_program_view("/nonexistent/prog.il", SoftCell::functions()), SourceError);
}

}  // namespace
}  // namespace plc_cell
