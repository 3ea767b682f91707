// The bridge's bus side: request planning, the YAML, and polling real slaves:
// our own, libmodbus's unit-test-server, pymodbus 3.0, and a silent RTU slave.
#include <condition_variable>
#include <fstream>
#include <mutex>

#include <gtest/gtest.h>

#include "helpers.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/io/serial_settings.h"
#include "plc_cell/modbus/bridge.h"
#include "plc_cell/modbus/rtu_server.h"
#include "../reliability/pty_proxy.h"
#include "plc_cell/modbus/tcp_server.h"

namespace plc_cell {
namespace modbus {
namespace {

// Collects results; waits block on a condition variable with a bound.
class Collector {
 public:
  void operator()(const GroupResult& r) {
    std::lock_guard<std::mutex> lk(mu_);
    results_.push_back(r);
    cv_.notify_all();
  }
  // The first result (from now on) satisfying pred, or fails the test after 10 s.
  GroupResult wait(const std::function<bool(const GroupResult&)>& pred, int timeout_s = 10) {
    std::unique_lock<std::mutex> lk(mu_);
    GroupResult found;
    const bool ok = cv_.wait_for(lk, std::chrono::seconds(timeout_s), [&] {
      for (; seen_ < results_.size(); ++seen_)
        if (pred(results_[seen_])) {
          found = results_[seen_++];
          return true;
        }
      return false;
    });
    EXPECT_TRUE(ok) << "no matching poll result";
    return found;
  }
  std::vector<GroupResult> all() {
    std::lock_guard<std::mutex> lk(mu_);
    return results_;
  }

 private:
  std::mutex mu_;
  std::condition_variable cv_;
  std::vector<GroupResult> results_;
  size_t seen_ = 0;
};

BridgeConfig yaml(const std::string& text) { return parse_bridge_config(YAML::Load(text), "bridge.yaml"); }

Point reg_point(uint32_t a, PointType t) {
  Point p;
  p.name = "p" + std::to_string(a);
  p.address = a;
  p.enc.type = t;
  return p;
}

TEST(BridgePlan, CoalescesWithinGapAndPduLimits) {
  std::vector<Point> pts = {reg_point(0, PointType::UInt16), reg_point(1, PointType::Float32),
                            reg_point(5, PointType::Int64), reg_point(100, PointType::UInt16),
                            reg_point(124, PointType::UInt16), reg_point(125, PointType::UInt16)};
  auto reads = plan_reads(pts, 8);
  // 0..8 (gap 3..4 bridged); 100; 124; 125: 100..125 spans 26 but the gap 101..123 is 23 > 8.
  ASSERT_EQ(reads.size(), 3u);
  EXPECT_EQ(reads[0].address, 0u);
  EXPECT_EQ(reads[0].count, 9u);
  EXPECT_EQ(reads[1].address, 100u);
  EXPECT_EQ(reads[1].count, 1u);
  EXPECT_EQ(reads[2].address, 124u);
  EXPECT_EQ(reads[2].count, 2u);
  // With unlimited gaps the 125-register PDU limit splits: 0..124 then 125.
  reads = plan_reads(pts, 1000);
  ASSERT_EQ(reads.size(), 2u);
  EXPECT_EQ(reads[0].count, 125u);
  EXPECT_EQ(reads[1].address, 125u);
  // Bits: 2000 per read.
  std::vector<Point> bits;
  for (uint32_t a : {0u, 1999u, 2000u}) {
    Point p;
    p.name = std::to_string(a);
    p.table = Table::Coils;
    p.address = a;
    p.enc.type = PointType::Bool;
    bits.push_back(p);
  }
  reads = plan_reads(bits, 5000);
  ASSERT_EQ(reads.size(), 2u);
  EXPECT_EQ(reads[0].count, 2000u);
}

TEST(BridgeConfigYaml, ReferencesAndErrors) {
  const auto cfg = yaml(R"(
devices:
  - name: meter
    tcp: 127.0.0.1:1502
    unit: 3
    groups:
      - name: fast
        rate: 20
        points:
          - {name: a, ref: "40001", type: float32, word_order: little}
          - {name: b, ref: "300010"}
          - {name: c, ref: "00003"}
          - {name: d, table: discrete_input, address: 7}
)");
  const auto& pts = cfg.devices[0].groups[0].points;
  EXPECT_EQ(pts[0].table, Table::HoldingRegisters);
  EXPECT_EQ(pts[0].address, 0u);
  EXPECT_EQ(pts[0].enc.word_order, Order::Little);
  EXPECT_EQ(pts[1].table, Table::InputRegisters);
  EXPECT_EQ(pts[1].address, 9u);
  EXPECT_EQ(pts[2].table, Table::Coils);
  EXPECT_EQ(pts[2].address, 2u);
  EXPECT_EQ(pts[3].enc.type, PointType::Bool);
  EXPECT_THROW(yaml("devices: [{name: x, groups: []}]"), Error);  // neither tcp nor rtu
  EXPECT_THROW(yaml("devices: [{name: x, tcp: ':1', groups: [{name: g, points: [{name: p, ref: '20001'}]}]}]"), Error);
  EXPECT_THROW(yaml("devices: [{name: x, tcp: ':1', groups: [{name: g, points: [{name: p, ref: '40001', type: bool}]}]}]"), Error);
  EXPECT_THROW(yaml("devices: [{name: x, rtu: /dev/a:9600, groups: []}, {name: y, rtu: /dev/a:19200, groups: []}]"), Error);
}

// The bridge YAML is read by the cell's YAML reader: every key is checked, an error names
// file:line:column and the key, and device and point names (topics ~<device>/<point>)
// are letters, digits and _ (docs/modbus.md).
std::string bridge_error(const std::string& name, const std::string& text, std::string* path) {
  *path = test::tmp_dir() + "/" + name;
  std::ofstream(*path) << text;
  try {
    load_bridge_config(*path);
  } catch (const SourceError& e) {
    return e.what();
  }
  return "no error";
}

TEST(BridgeConfigYaml, ErrorsNameFileLineAndKey) {
  const std::string head =
      "devices:\n  - name: meter\n    tcp: 127.0.0.1:1502\n    groups:\n      - name: g\n        points:\n";
  std::string f;
  std::string e = bridge_error("ref.yaml", head + "          - {name: a, ref: \"20001\"}\n", &f);
  EXPECT_EQ(e, f + ":7:28: error: key 'devices[0].groups[0].points[0].ref': ref '20001' starts with 2 (expected 0, 1, 3 or 4)");
  e = bridge_error("key.yaml", head + "          - {name: a, adress: 3}\n", &f);
  EXPECT_EQ(e, f + ":7:23: error: key 'devices[0].groups[0].points[0].adress': unknown key (expected one of: address, "
                   "byte_order, name, offset, ref, scale, table, type, word_order)");
  e = bridge_error("top.yaml", "backof_min: 1\ndevices: []\n", &f);
  EXPECT_EQ(e, f + ":1:1: error: key 'backof_min': unknown key (expected one of: backoff_max, backoff_min, devices)");
  e = bridge_error("device.yaml", "devices:\n  - name: my-meter\n    tcp: 127.0.0.1:1502\n    groups: []\n", &f);
  EXPECT_EQ(e, f + ":2:11: error: key 'devices[0].name': a device name is letters, digits and _ (it becomes a ROS topic name)");
  e = bridge_error("line.yaml",
                   "devices:\n  - {name: a, rtu: /dev/a:9600, groups: []}\n  - {name: b, rtu: /dev/a:19200, groups: []}\n", &f);
  EXPECT_EQ(e.rfind(f + ":3:20: error: key 'devices[1].rtu': serial line rtu:/dev/a already set up as ", 0), 0u) << e;
  e = bridge_error("twice.yaml", head + "          - {name: a, ref: \"40001\"}\n          - {name: a, ref: \"40002\"}\n", &f);
  EXPECT_EQ(e, f + ":8:20: error: key 'devices[0].groups[0].points[1].name': point 'a' defined twice on this device");
  e = bridge_error("syntax.yaml", "devices: [\n", &f);
  EXPECT_EQ(e.rfind(f + ":2:", 0), 0u) << e;
  EXPECT_NE(e.find("YAML syntax"), std::string::npos) << e;
}

TEST(BridgeConfigYaml, TheShippedExampleLoads) {
  const auto cfg = load_bridge_config(std::string(PLC_CELL_SOURCE_DIR) + "/examples/modbus/bridge_example.yaml");
  ASSERT_EQ(cfg.devices.size(), 3u);
  EXPECT_EQ(cfg.devices[0].line(), cfg.devices[1].line());  // meter and PLC share the RS-485 line
  EXPECT_EQ(cfg.devices[1].groups[0].points[3].address, 9700u);  // 49701 = C200
}

TEST(Bridge, ReadsAndWritesOurSlave) {
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  TcpServer slave(plc, o);
  slave.start();
  plc.locked([](ScanEngine&, Memory& m) {
    m.set_reg(Area::R, 0, 0xFFFE);                      // int16 -2
    m.set_reg(Area::R, 1, 0xF5C3);                      // float32 3.14, CDAB
    m.set_reg(Area::R, 2, 0x4048);
    m.write(parse_address("DRC200"), 123456789);        // 49701/49702, low word first
    m.set_bit(Area::Y, 4, true);
    m.set_reg(Area::D, 10, 250);                        // 25.0 with scale 0.1
    return 0;
  });
  Collector c;
  Bridge b(yaml(R"(
devices:
  - name: plc
    tcp: 127.0.0.1:)" + std::to_string(slave.bound_port()) + R"(
    groups:
      - name: g
        rate: 50
        points:
          - {name: i16, address: 0, type: int16}
          - {name: f32, address: 1, type: float32, word_order: little}
          - {name: c200, address: 9700, type: uint32, word_order: little}
          - {name: y4, table: coil, address: 4}
          - {name: temp, address: 6010, type: uint16, scale: 0.1}
)"),
           std::ref(c));
  b.start();
  GroupResult r = c.wait([](const GroupResult& x) { return x.ok; });
  ASSERT_EQ(r.values.size(), 5u);
  EXPECT_EQ(r.values[0].as_int64(), -2);
  EXPECT_FLOAT_EQ(float(r.values[1].as_double()), 3.14f);
  EXPECT_EQ(r.values[2].as_uint64(), 123456789u);
  EXPECT_EQ(r.values[3].raw, 1u);
  EXPECT_DOUBLE_EQ(r.engineering[4], 25.0);
  EXPECT_EQ(r.reads.size(), 4u);  // R0..R2, C200, Y4, D10: different areas, far apart

  b.write("plc/f32", -1.5);  // 0xBFC00000 word-swapped
  EXPECT_EQ(plc.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 1); }), 0x0000);
  EXPECT_EQ(plc.locked([](ScanEngine&, Memory& m) { return m.reg(Area::R, 2); }), 0xBFC0);
  b.write("temp", 30.2);
  EXPECT_EQ(plc.locked([](ScanEngine&, Memory& m) { return m.reg(Area::D, 10); }), 302);
  b.write("y4", 0);
  EXPECT_FALSE(plc.locked([](ScanEngine&, Memory& m) { return m.bit(Area::Y, 4); }));
  // A refused value names the point and its type, and is shown as it was written.
  const auto refusal = [&](const std::string& point, double v) {
    try {
      b.write(point, v);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("i16", 40000), "point 'i16' (int16): value 40000 does not fit int16 (-32768..32767)");
  EXPECT_EQ(refusal("plc/i16", -32768.75), "point 'plc/i16' (int16): value -32768.75 does not fit int16 (-32768..32767)");
  EXPECT_EQ(refusal("temp", 7000),  // scale 0.1: the raw value is said too
            "point 'temp' (uint16): value 7000 (raw 70000) does not fit uint16 (0..65535)");
  EXPECT_THROW(b.write("nope", 1), Error);
  // A later poll reads back every value written (one that went out between two of the
  // writes holds some of them only: not that one).
  c.wait([](const GroupResult& x) {
    return x.ok && x.values[1].as_double() == -1.5 && x.values[3].raw == 0 && x.values[4].raw == 302;
  });
  EXPECT_TRUE(b.status(0).connected);
  EXPECT_GE(b.status(0).writes, 3u);
  b.stop();
}

TEST(Bridge, ExceptionRepliesAreCountedAndTheLinkKept) {
  Plc plc;
  TcpServerOptions o;
  o.port = 0;
  TcpServer slave(plc, o);
  slave.start();
  Collector c;
  Bridge b(yaml(R"(
devices:
  - name: plc
    tcp: 127.0.0.1:)" + std::to_string(slave.bound_port()) + R"(
    groups:
      - {name: bad, rate: 50, points: [{name: gap, address: 4168}]}
      - {name: good, rate: 50, points: [{name: r0, address: 0}]}
)"),
           std::ref(c));
  b.start();
  const GroupResult bad = c.wait([](const GroupResult& x) { return x.group == 0; });
  EXPECT_FALSE(bad.ok);
  c.wait([](const GroupResult& x) { return x.group == 1 && x.ok; });
  const DeviceStatus s = b.status(0);
  EXPECT_GE(s.exceptions, 1u);
  EXPECT_EQ(s.last_exception.substr(0, 2), "02");
  EXPECT_TRUE(s.connected);
  b.stop();
}

TEST(Bridge, AgainstLibmodbusUnitTestServer) {
  const std::string bin = test::build_example(
      "unit-test-server", {{"modbus_set_debug(ctx, TRUE);", "modbus_set_debug(ctx, FALSE);"}}, "tcp");
  test::Child server({bin, "tcp"});  // 127.0.0.1:1502; the bridge retries until it listens
  Collector c;
  Bridge b(yaml(R"(
backoff_min: 0.05
devices:
  - name: ut
    tcp: 127.0.0.1:1502
    unit: 17
    groups:
      - name: g
        rate: 20
        points:
          - {name: ir, table: input_register, address: 0x108}
          - {name: in0, table: discrete_input, address: 0x1C4}
          - {name: in2, table: discrete_input, address: 0x1C6}
          - {name: hr, address: 0x160, type: uint32}
          - {name: hr2, address: 0x162}  # a 2-register read is one of the server's special cases
)"),
           std::ref(c));
  b.start();
  GroupResult r = c.wait([](const GroupResult& x) { return x.ok; });
  ASSERT_EQ(r.values.size(), 5u) << "no poll of the server succeeded (is 127.0.0.1:1502 another's?)";
  EXPECT_EQ(r.values[0].raw, 10u);  // UT_INPUT_REGISTERS_TAB
  EXPECT_EQ(r.values[1].raw, 0u);   // UT_INPUT_BITS_TAB[0] = 0xAC: bit 0 off, bit 2 on
  EXPECT_EQ(r.values[2].raw, 1u);
  b.write("hr", 0x12345678);
  r = c.wait([](const GroupResult& x) { return x.ok && x.values[3].raw == 0x12345678u; });
  ASSERT_FALSE(r.blocks.empty());
  EXPECT_EQ(r.blocks.back()[0], 0x1234);  // ABCD: high word first
  b.stop();
}

TEST(Bridge, AgainstLibmodbusRandomTestServer) {
  const std::string bin = test::build_example("random-test-server", {}, "tcp");
  test::Child server({bin});  // 127.0.0.1:1502, 500 of each table, all zero
  Collector c;
  Bridge b(yaml(R"(
backoff_min: 0.05
devices:
  - name: rnd
    tcp: 127.0.0.1:1502
    groups:
      - name: g
        rate: 20
        points:
          - {name: d, address: 100, type: float64, byte_order: little, word_order: little}
          - {name: i, address: 104, type: int32, word_order: little}
          - {name: coil, table: coil, address: 499}
)"),
           std::ref(c));
  b.start();
  c.wait([](const GroupResult& x) { return x.ok; });
  b.write("d", -1234.5678);
  b.write("i", -7);
  b.write("coil", 1);
  const GroupResult r = c.wait([](const GroupResult& x) {
    return x.ok && x.values[0].as_double() == -1234.5678 && x.values[1].as_int64() == -7 && x.values[2].raw == 1;
  });
  EXPECT_EQ(r.reads.size(), 2u);  // registers 100..105 in one read, the coil in another
  b.stop();
}

TEST(Bridge, AgainstPymodbus) {
  const int port = 15020;
  test::Child server({"/usr/bin/python3", std::string(PLC_CELL_SOURCE_DIR) + "/test/modbus/pymodbus_server.py",
                      std::to_string(port)});
  ASSERT_TRUE(server.wait_for("pymodbus server")) << server.seen();
  Collector c;
  Bridge b(yaml(R"(
backoff_min: 0.05
devices:
  - name: py
    tcp: 127.0.0.1:)" + std::to_string(port) + R"(
    groups:
      - name: g
        rate: 20
        points:
          - {name: f, address: 10, type: float32}
          - {name: i, address: 20, type: int16}
          - {name: u64, address: 30, type: uint64}
          - {name: ir, table: input_register, address: 3}
          - {name: co, table: coil, address: 5}
)"),
           std::ref(c));
  b.start();
  GroupResult r = c.wait([](const GroupResult& x) { return x.ok; }, 30);
  ASSERT_EQ(r.values.size(), 5u);
  EXPECT_FLOAT_EQ(float(r.values[0].as_double()), 3.14f);
  EXPECT_EQ(r.values[1].as_int64(), -2);
  EXPECT_EQ(r.values[2].as_uint64(), 65536u);
  EXPECT_EQ(r.values[3].raw, 777u);
  EXPECT_EQ(r.values[4].raw, 1u);
  // HR 10..20 (gap of 8 bridged), HR 30..33 (gap of 9 is not), IR, coils.
  EXPECT_EQ(r.reads.size(), 4u);
  b.write("py/f", 2.5);
  r = c.wait([](const GroupResult& x) { return x.ok && x.values[0].as_double() == 2.5; });
  b.stop();
}

TEST(Bridge, TwoDevicesOnOneRtuLineOneSilent) {
  test::PtyPair pty("bridge");
  Plc plc;
  plc.locked([](ScanEngine&, Memory& m) { m.set_reg(Area::R, 0, 42); return 0; });
  RtuServer slave(plc, parse_serial_settings(pty.a + ":115200:8E1"), 1);
  slave.start();
  Collector c;
  Bridge b(yaml(R"(
devices:
  - name: plc
    rtu: )" + pty.b + R"(:115200:8E1
    unit: 1
    timeout: 1.0
    groups: [{name: g, rate: 20, points: [{name: r0, address: 0}]}]
  - name: ghost
    rtu: )" + pty.b + R"(:115200:8E1
    unit: 2
    timeout: 0.3
    groups: [{name: g, rate: 20, points: [{name: r0, address: 0}]}]
)"),
           std::ref(c));
  b.start();
  c.wait([](const GroupResult& x) { return x.device == 1 && !x.ok; });
  const GroupResult r = c.wait([](const GroupResult& x) { return x.device == 0 && x.ok; });
  EXPECT_EQ(r.values[0].raw, 42u);
  c.wait([](const GroupResult& x) { return x.device == 0 && x.ok; });  // still served after the timeouts
  EXPECT_GE(b.status(1).timeouts, 1u);
  EXPECT_EQ(b.status(0).timeouts, 0u) << b.status(0).last_error;
  b.stop();
}

// A slave that answers late but in order (the soft PLC's RTU slave behind a proxy that
// holds each reply back 300 ms; timeout 200 ms). Two one-register groups of the same slave
// have replies alike but for their value: a late reply must never pass for the other
// group's; once the slave answers in time the line delivers the true values. After a
// timeout the line is drained until quiet for the timeout, so the replies come between the
// timeout and twice it, 100 ms from either: a loaded machine's late threads do not make
// a reply in time, nor one later than the drain.
TEST(Bridge, ALateRtuReplyIsNeverTakenForTheNextRequest) {
  {
    LateDeviceLine proxy(300);
    Plc plc;
    plc.locked([](ScanEngine&, Memory& m) {
      m.set_reg(Area::R, 0, 111);
      m.set_reg(Area::R, 1, 222);
      return 0;
    });
    RtuServer slave(plc, parse_serial_settings(proxy.device_link() + ":115200:8E1"), 1);
    slave.start();
    Collector c;
    Bridge b(yaml(R"(
devices:
  - name: plc
    rtu: )" + proxy.client_link() + R"(:115200:8E1
    unit: 1
    timeout: 0.2
    groups:
      - {name: a, rate: 20, points: [{name: r0, address: 0}]}
      - {name: b, rate: 20, points: [{name: r1, address: 1}]}
)"),
             std::ref(c));
    b.start();
    const auto only_true_values = [&] {
      for (const auto& r : c.all())
        if (r.ok) {
          EXPECT_EQ(r.values.at(0).raw, r.group == 0 ? 111u : 222u) << "group " << r.group;
        }
    };
    c.wait([&](const GroupResult&) { return b.status(0).timeouts >= 4; }, 30);
    only_true_values();
    for (const auto& r : c.all()) EXPECT_FALSE(r.ok);
    proxy.set_delay_ms(0);
    c.wait([](const GroupResult& x) { return x.ok && x.group == 0; }, 30);
    c.wait([](const GroupResult& x) { return x.ok && x.group == 1; }, 30);
    b.stop();
    slave.stop();
    only_true_values();
  }
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
