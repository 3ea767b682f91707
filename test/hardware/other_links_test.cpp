// `plc_cell test --target` over the TRi host link and Modbus TCP and RTU, with `plc_cell run`
// standing in for the PLC (its FATEK server beside, for the test to see the state), and the
// forms of --target and the FBs Modbus map turned around.
#include <fstream>

#include "../harness/pty_pair.h"
#include "hardware_fixture.h"
#include "plc_cell/hardware/modbus_plc.h"
#include "plc_cell/hardware/target_spec.h"

namespace hardware_test {
namespace {

using plc_cell::parse_address;
using plc_cell::hardware::fbs_modbus_place;

const std::vector<std::string> kRelayPoints = {"M10", "D0", "D1", "Y5"};

// The relay cell served by `plc_cell run` with the given servers besides its FATEK TCP one.
class LinkTarget : public HardwareTest {
 protected:
  std::unique_ptr<RunChild> serve(std::vector<std::string> servers) {
    std::vector<std::string> args = {"--config", kRelayCell, "--fatek-tcp", "127.0.0.1:0"};
    args.insert(args.end(), servers.begin(), servers.end());
    auto c = std::make_unique<RunChild>(args);
    wait_scanning(*c);
    return c;
  }
  // The relay scenario passes on target and leaves the PLC as found.
  void passes_and_restores(const RunChild& plc, const std::string& target, const std::string& named,
                           const std::vector<std::string>& options = {}) {
    const int fatek = port_of(plc, "FATEK TCP");
    plc_cell::fatek::Client(plc_cell::fatek::tcp_transport(loopback(fatek))).write(parse_address("D0"), {55});
    for (int i = 0; i < 1000 && state_of(fatek, {"D1"}).values[0] != 55; ++i) {
    }
    const PlcState before = state_of(fatek, kRelayPoints);
    ASSERT_EQ(before.values[2], 55u) << "D1 never mirrored D0";
    std::vector<std::string> args = {kRelayScenario, "--target", target};
    args.insert(args.end(), options.begin(), options.end());
    const auto r = test_tool(args);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(r.out.rfind("plc_cell test on " + named, 0), 0u) << r.out;
    EXPECT_NE(r.out.find("PASS  " + kRelayScenario + ": a request runs the timer and the mirror follows"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("D0: written back, 55 as found"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("; the PLC is as it was found\n"), std::string::npos) << r.out;
    for (int i = 0; i < 1000 && state_of(fatek, {"D1"}).values[0] != 55; ++i) {
    }
    const PlcState after = state_of(fatek, kRelayPoints);
    EXPECT_TRUE(after == before) << describe(before, kRelayPoints) << "\n" << describe(after, kRelayPoints);
  }
};

TEST_F(LinkTarget, OverTheTriHostLinkOnTcp) {
  const auto plc = serve({"--tri-tcp", "127.0.0.1:0"});
  passes_and_restores(*plc, "tri://" + loopback(port_of(*plc, "TRi TCP")),
                      "TRi tcp " + loopback(port_of(*plc, "TRi TCP")) + " ID 01");
}

TEST_F(LinkTarget, OverTheTriHostLinkOnASerialLine) {
  plc_cell::testing::PtyPair line(temp());
  const auto plc = serve({"--tri-serial", line.b});
  passes_and_restores(*plc, "tri-serial:" + line.a, "TRi ");
}

TEST_F(LinkTarget, OverModbusTcp) {
  const auto plc = serve({"--modbus-tcp", "127.0.0.1:0"});
  passes_and_restores(*plc, "modbus://" + loopback(port_of(*plc, "Modbus TCP")),
                      "Modbus tcp " + loopback(port_of(*plc, "Modbus TCP")) + " unit 1");
}

TEST_F(LinkTarget, OverModbusRtuThroughSocat) {
  plc_cell::testing::PtyPair line(temp());
  const auto plc = serve({"--modbus-rtu", line.b, "--modbus-id", "3"});
  passes_and_restores(*plc, "modbus-rtu:" + line.a, "Modbus RTU ", {"--id", "3"});
  // Another unit id gets no answer: said, and nothing runs.
  const auto r = test_tool({kRelayScenario, "--target", "modbus-rtu:" + line.a, "--timeout", "100ms"});
  EXPECT_EQ(r.status, 1) << r.out;
  EXPECT_NE(r.out.find("plc_cell test: cannot reach Modbus RTU "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("; no case ran, nothing was written"), std::string::npos) << r.out;
}

// The TRi has no DISABLE flag: a case that holds an input is refused at its line, naming
// why, and nothing is written; the same file's other case is not run either.
TEST_F(LinkTarget, TheTriCannotHoldAnInputAndSaysSoBeforeAnythingIsWritten) {
  const auto plc = serve({"--tri-tcp", "127.0.0.1:0"});
  const std::string file = temp() + "/hold.scenario.yaml";
  std::ofstream(file) << "cell: " << kRelayCell
                      << "\nhardware: {require_run: false}\ncases:\n"
                         "  - name: writes\n    steps:\n      - write: {D0: 9}\n"
                         "  - name: holds\n    steps:\n      - set: {X2: on}\n      - force: {Y5: off}\n";
  const int fatek = port_of(*plc, "FATEK TCP");
  const PlcState before = state_of(fatek, {"D0", "X2", "Y5"});
  const auto r = test_tool({file, "--target", "tri://" + loopback(port_of(*plc, "TRi TCP"))});
  EXPECT_EQ(r.status, 1) << r.out;
  const std::string why = "TRi tcp " + loopback(port_of(*plc, "TRi TCP")) +
                          " ID 01 cannot hold it: the TRi has no DISABLE flag, so its host link cannot hold a point "
                          "(write it instead)";
  EXPECT_NE(r.out.find(file + ":9: error: key 'set': X2: " + why), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(file + ":10: error: key 'force': done (Y5): " + why), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("no case ran, nothing was written"), std::string::npos) << r.out;
  EXPECT_TRUE(state_of(fatek, {"D0", "X2", "Y5"}) == before);
}

TEST(TargetForms, EachFormItsOptionAndWhatIsWrongWithAText) {
  auto error = [](plc_cell::hardware::TargetOptions o) {
    try {
      plc_cell::hardware::open_target(o);
      return std::string();
    } catch (const plc_cell::Error& e) {
      return std::string(e.what());
    }
  };
  plc_cell::hardware::TargetOptions o;
  o.text = "fatek://127.0.0.1:500";
  EXPECT_EQ(plc_cell::hardware::open_target(o)->describe(), "FATEK tcp 127.0.0.1:500 station 1");
  o.text = "s7://10.0.0.1:102";
  EXPECT_EQ(error(o),
            "--target s7://10.0.0.1:102: expected one of fatek://HOST:PORT, fatek-serial:DEVICE[:BAUD[:FORMAT]], "
            "tri://HOST:PORT, tri-serial:DEVICE[:BAUD[:FORMAT]], modbus://HOST:PORT, modbus-rtu:DEVICE[:BAUD[:FORMAT]]");
  o.text = "tri://127.0.0.1:9080";
  o.station = 2;
  EXPECT_EQ(error(o), "--station does not go with tri:// (it takes --id)");
  o.station.reset();
  o.text = "modbus://127.0.0.1:502";
  o.id = 0;
  EXPECT_EQ(error(o), "--id 0: out of range 1..247 for modbus://");
  o.id.reset();
  o.text = "fatek-serial:ttyUSB0";
  EXPECT_EQ(error(o), "fatek-serial:: 'ttyUSB0' is not a device path (/dev/ttyUSB0, /dev/ttyUSB0:9600:7E1)");
  o.text = "fatek://127.0.0.1";
  EXPECT_NE(error(o), "");
}

TEST(FbsModbusMap, EveryRowOfTheDefaultMapTurnedAround) {
  struct Row {
    const char* address;
    bool coils;
    uint32_t first, count;
  };
  // docs/modbus.md, "Default map".
  for (const Row& r : {Row{"Y0", true, 0, 1}, Row{"Y255", true, 255, 1}, Row{"X0", true, 1000, 1},
                       Row{"M0", true, 2000, 1}, Row{"M2001", true, 4001, 1}, Row{"S999", true, 6999, 1},
                       Row{"T255", true, 9255, 1}, Row{"C0", true, 9500, 1}, Row{"WY16", true, 16, 16},
                       Row{"R0", false, 0, 1}, Row{"R4167", false, 4167, 1}, Row{"R5000", false, 5000, 1},
                       Row{"D0", false, 6000, 1}, Row{"D2998", false, 8998, 1}, Row{"RT5", false, 9005, 1},
                       Row{"RC199", false, 9699, 1}, Row{"DRC200", false, 9700, 2}, Row{"DRC255", false, 9810, 2},
                       Row{"DR10", false, 10, 2}, Row{"DD4", false, 6004, 2}}) {
    const auto p = fbs_modbus_place(parse_address(r.address));
    EXPECT_EQ(p.coils, r.coils) << r.address;
    EXPECT_EQ(p.first, r.first) << r.address;
    EXPECT_EQ(p.count, r.count) << r.address;
  }
  for (const char* out : {"R4168", "R5999", "D2999", "M2002", "DR4167", "F0", "S1000"})
    EXPECT_THROW(fbs_modbus_place(parse_address(out)), plc_cell::Error) << out;
}

}  // namespace
}  // namespace hardware_test
