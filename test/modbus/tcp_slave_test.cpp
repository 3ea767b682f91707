// The TCP slave with libmodbus as the client, in process (any free port), and
// raw sockets for the malformed input.
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <vector>
#include <sys/socket.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <modbus/modbus.h>

#include "plc_cell/core/plc.h"
#include "plc_cell/modbus/tcp_server.h"

namespace plc_cell {
namespace modbus {
namespace {

class TcpSlave : public ::testing::Test {
 protected:
  void SetUp() override { start(); }
  void TearDown() override {
    if (client) {
      modbus_close(client);
      modbus_free(client);
    }
    server->stop();
  }
  void start(int max_conn = 16, int idle_ms = 60000) {
    TcpServerOptions o;
    o.port = 0;
    o.max_connections = max_conn;
    o.idle_timeout_ms = idle_ms;
    server = std::make_unique<TcpServer>(plc, o);
    server->start();
    client = connect_client();
  }
  modbus_t* connect_client() {
    modbus_t* c = modbus_new_tcp("127.0.0.1", server->bound_port());
    modbus_set_response_timeout(c, 5, 0);
    EXPECT_EQ(modbus_connect(c), 0);
    return c;
  }
  uint16_t reg(Area a, uint32_t i) { return plc.locked([&](ScanEngine&, Memory& m) { return m.reg(a, i); }); }
  bool bit(Area a, uint32_t i) { return plc.locked([&](ScanEngine&, Memory& m) { return m.bit(a, i); }); }
  void set_reg(Area a, uint32_t i, uint16_t v) {
    plc.locked([&](ScanEngine&, Memory& m) { m.set_reg(a, i, v); return 0; });
  }
  int raw_socket() {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in sa{};
    sa.sin_family = AF_INET;
    sa.sin_port = htons(uint16_t(server->bound_port()));
    sa.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    EXPECT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&sa), sizeof sa), 0);
    return fd;
  }
  // Blocks up to 5 s for a reply: its length, 0 when the server closed the
  // connection (FIN, or RST when it closed with our bytes unread), -1 on timeout.
  static int read_reply(int fd, uint8_t* buf, int cap) {
    pollfd p{fd, POLLIN, 0};
    if (poll(&p, 1, 5000) <= 0) return -1;
    const ssize_t n = recv(fd, buf, size_t(cap), 0);
    return n < 0 && errno == ECONNRESET ? 0 : int(n);
  }

  Plc plc;
  std::unique_ptr<TcpServer> server;
  modbus_t* client = nullptr;
};

TEST_F(TcpSlave, RegistersLandInTheMappedAreas) {
  const uint16_t w[] = {11, 22, 33};
  ASSERT_EQ(modbus_write_registers(client, 100, 3, w), 3);  // 40101 = R100
  EXPECT_EQ(reg(Area::R, 100), 11);
  EXPECT_EQ(reg(Area::R, 102), 33);
  ASSERT_EQ(modbus_write_register(client, 6000 + 7, 4242), 1);  // 46008 = D7
  EXPECT_EQ(reg(Area::D, 7), 4242);
  ASSERT_EQ(modbus_write_register(client, 9003, 5), 1);  // T3 current value
  EXPECT_EQ(reg(Area::RT, 3), 5);
  // C200 is 32 bits: 49701 low word, 49702 high word.
  const uint16_t c200[] = {0x5678, 0x1234};
  ASSERT_EQ(modbus_write_registers(client, 9700, 2, c200), 2);
  const uint32_t v = plc.locked([](ScanEngine&, Memory& m) { return m.read(parse_address("DRC200")); });
  EXPECT_EQ(v, 0x12345678u);
  set_reg(Area::R, 4167, 77);
  uint16_t r[1];
  ASSERT_EQ(modbus_read_registers(client, 4167, 1, r), 1);
  EXPECT_EQ(r[0], 77);
}

TEST_F(TcpSlave, CoilsLandInTheMappedAreas) {
  ASSERT_EQ(modbus_write_bit(client, 5, 1), 1);  // Y5
  EXPECT_TRUE(bit(Area::Y, 5));
  const uint8_t b[] = {1, 0, 1};
  ASSERT_EQ(modbus_write_bits(client, 2000 + 10, 3, b), 3);  // M10..M12
  EXPECT_TRUE(bit(Area::M, 10));
  EXPECT_FALSE(bit(Area::M, 11));
  EXPECT_TRUE(bit(Area::M, 12));
  plc.locked([](ScanEngine&, Memory& m) { m.set_bit(Area::S, 999, true); m.set_bit(Area::C, 255, true); return 0; });
  uint8_t rd[1];
  ASSERT_EQ(modbus_read_bits(client, 6999, 1, rd), 1);
  EXPECT_EQ(rd[0], 1);
  ASSERT_EQ(modbus_read_bits(client, 9755, 1, rd), 1);
  EXPECT_EQ(rd[0], 1);
}

TEST_F(TcpSlave, ForcedPointsKeepTheirState) {
  plc.locked([](ScanEngine&, Memory& m) { m.set_disabled(Area::Y, 7, true); return 0; });
  ASSERT_EQ(modbus_write_bit(client, 7, 1), 1);
  EXPECT_FALSE(bit(Area::Y, 7));
}

TEST_F(TcpSlave, WriteAndReadRegisters) {
  set_reg(Area::R, 10, 99);
  const uint16_t w[] = {1, 2};
  uint16_t r[3];
  ASSERT_EQ(modbus_write_and_read_registers(client, 6000, 2, w, 9, 3, r), 3);
  EXPECT_EQ(reg(Area::D, 0), 1);
  EXPECT_EQ(reg(Area::D, 1), 2);
  EXPECT_EQ(r[1], 99);
}

TEST_F(TcpSlave, StandardExceptionsAndNothingChanges) {
  uint16_t r[2];
  EXPECT_EQ(modbus_read_registers(client, 4168, 1, r), -1);
  EXPECT_EQ(errno, EMBXILADD);
  // A write that runs off the end of R4167 is refused whole.
  const uint16_t w[] = {1, 2};
  EXPECT_EQ(modbus_write_registers(client, 4167, 2, w), -1);
  EXPECT_EQ(errno, EMBXILADD);
  EXPECT_EQ(reg(Area::R, 4167), 0);
  uint8_t b[1];
  EXPECT_EQ(modbus_read_input_bits(client, 0, 1, b), -1);  // no 1x space by default
  EXPECT_EQ(errno, EMBXILADD);
  // Raw frames for what libmodbus as a client would not send.
  const int raw = raw_socket();
  const auto exception_of = [&](std::vector<uint8_t> pdu) {
    std::vector<uint8_t> f = {0, 7, 0, 0, 0, uint8_t(pdu.size() + 1), 1};
    f.insert(f.end(), pdu.begin(), pdu.end());
    EXPECT_EQ(send(raw, f.data(), f.size(), 0), ssize_t(f.size()));
    uint8_t buf[300];
    const int n = read_reply(raw, buf, sizeof buf);
    EXPECT_EQ(n, 9);
    EXPECT_EQ(buf[7], pdu[0] | 0x80);
    return n == 9 ? int(buf[8]) : -1;
  };
  EXPECT_EQ(exception_of({0x03, 0, 0, 0, 126}), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);  // over the PDU limit
  EXPECT_EQ(exception_of({0x03, 0, 0, 0, 0}), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);    // quantity 0
  EXPECT_EQ(exception_of({0x05, 0, 3, 0x12, 0x34}), MODBUS_EXCEPTION_ILLEGAL_DATA_VALUE);  // not FF00/0000
  EXPECT_FALSE(bit(Area::Y, 3));
  // FC23 whose write part is fine but whose read part is unmapped: nothing written.
  EXPECT_EQ(exception_of({0x17, 0x10, 0x48, 0, 1, 0, 50, 0, 1, 2, 0xAB, 0xCD}), MODBUS_EXCEPTION_ILLEGAL_DATA_ADDRESS);
  EXPECT_EQ(reg(Area::R, 50), 0);
  close(raw);
  // Report slave id (0x11), diagnostics (0x08), encapsulated transport (0x2B): not FBs functions.
  const int fd = raw_socket();
  for (uint8_t fc : {0x11, 0x08, 0x2B}) {
    const uint8_t req[] = {0, 9, 0, 0, 0, uint8_t(fc == 0x11 ? 2 : 6), 1, fc, 0, 0, 0, 0};
    ASSERT_EQ(send(fd, req, fc == 0x11 ? 8 : 12, 0), fc == 0x11 ? 8 : 12);
    uint8_t buf[300];
    ASSERT_EQ(read_reply(fd, buf, sizeof buf), 9) << int(fc);
    EXPECT_EQ(buf[7], fc | 0x80);
    EXPECT_EQ(buf[8], MODBUS_EXCEPTION_ILLEGAL_FUNCTION);
  }
  close(fd);
}

TEST_F(TcpSlave, UserMapAtRequestTime) {
  uint16_t r[1];
  EXPECT_EQ(modbus_read_input_registers(client, 50, 1, r), -1);
  const uint16_t map[] = {0xA55A, 0, 1000, 100, 10, 1100, 50, 50, 1000, 10, 100, 2000, 200};
  ASSERT_EQ(modbus_write_registers(client, 3968, 13, map), 13);
  set_reg(Area::R, 1000, 31);
  ASSERT_EQ(modbus_read_input_registers(client, 50, 1, r), 1);  // 300051 = R1000
  EXPECT_EQ(r[0], 31);
  ASSERT_EQ(modbus_write_register(client, 100, 55), 1);  // 400101 = R2000
  EXPECT_EQ(reg(Area::R, 2000), 55);
  ASSERT_EQ(modbus_write_bit(client, 0, 1), 1);  // 000001 = M1000
  EXPECT_TRUE(bit(Area::M, 1000));
  plc.locked([](ScanEngine&, Memory& m) { m.set_bit(Area::M, 1100, true); return 0; });
  uint8_t b[1];
  ASSERT_EQ(modbus_read_input_bits(client, 10, 1, b), 1);  // 100011 = M1100
  EXPECT_EQ(b[0], 1);
  EXPECT_EQ(modbus_read_registers(client, 3968, 1, r), -1);  // R3968 no longer at 43969
  EXPECT_EQ(errno, EMBXILADD);
}

TEST_F(TcpSlave, MalformedInputIsRefusedAndOthersKeepBeingServed) {
  set_reg(Area::R, 1, 1234);
  const uint16_t before = reg(Area::R, 0);
  // 1. Protocol id not 0: the stream cannot be trusted, the connection is closed.
  {
    const int fd = raw_socket();
    const uint8_t f[] = {0, 1, 0, 7, 0, 6, 1, 6, 0, 0, 0, 9};
    ASSERT_EQ(send(fd, f, sizeof f, 0), ssize_t(sizeof f));
    uint8_t buf[300];
    EXPECT_EQ(read_reply(fd, buf, sizeof buf), 0);
    close(fd);
  }
  // 2. MBAP length that a frame cannot have (1 and 300).
  for (int len : {1, 300}) {
    const int fd = raw_socket();
    const uint8_t f[] = {0, 1, 0, 0, uint8_t(len >> 8), uint8_t(len), 1, 6};
    ASSERT_EQ(send(fd, f, sizeof f, 0), ssize_t(sizeof f));
    uint8_t buf[300];
    EXPECT_EQ(read_reply(fd, buf, sizeof buf), 0) << len;
    close(fd);
  }
  // 3. Length disagreeing with the PDU (FC06 with a stray byte): exception 03, stays open.
  const int fd = raw_socket();
  {
    const uint8_t f[] = {0, 2, 0, 0, 0, 7, 1, 6, 0, 0, 0, 9, 0xEE};
    ASSERT_EQ(send(fd, f, sizeof f, 0), ssize_t(sizeof f));
    uint8_t buf[300];
    ASSERT_EQ(read_reply(fd, buf, sizeof buf), 9);
    EXPECT_EQ(buf[7], 0x86);
    EXPECT_EQ(buf[8], 0x03);
  }
  // 4. FC16 whose byte count disagrees with the quantity: exception 03.
  {
    const uint8_t f[] = {0, 3, 0, 0, 0, 9, 1, 16, 0, 0, 0, 2, 2, 0, 5};
    ASSERT_EQ(send(fd, f, sizeof f, 0), ssize_t(sizeof f));
    uint8_t buf[300];
    ASSERT_EQ(read_reply(fd, buf, sizeof buf), 9);
    EXPECT_EQ(buf[7], 0x90);
    EXPECT_EQ(buf[8], 0x03);
  }
  // 5. Unknown function code with a payload: exception 01, same connection still works.
  {
    const uint8_t f[] = {0, 4, 0, 0, 0, 5, 1, 0x41, 1, 2, 3};
    ASSERT_EQ(send(fd, f, sizeof f, 0), ssize_t(sizeof f));
    uint8_t buf[300];
    ASSERT_EQ(read_reply(fd, buf, sizeof buf), 9);
    EXPECT_EQ(buf[7], 0xC1);
    EXPECT_EQ(buf[8], 0x01);
    const uint8_t rd[] = {0, 5, 0, 0, 0, 6, 1, 3, 0, 1, 0, 1};
    ASSERT_EQ(send(fd, rd, sizeof rd, 0), ssize_t(sizeof rd));
    ASSERT_EQ(read_reply(fd, buf, sizeof buf), 11);
    EXPECT_EQ(buf[9] << 8 | buf[10], 1234);
  }
  // 6. A stalling client: half a frame, then nothing. Others are served meanwhile.
  const int stall = raw_socket();
  const uint8_t half[] = {0, 6, 0, 0, 0, 6, 1, 6, 0};
  ASSERT_EQ(send(stall, half, sizeof half, 0), ssize_t(sizeof half));
  uint16_t r[2];
  for (int i = 0; i < 20; ++i) ASSERT_EQ(modbus_read_registers(client, 0, 2, r), 2);
  EXPECT_EQ(r[1], 1234);
  EXPECT_EQ(reg(Area::R, 0), before);
  close(stall);
  close(fd);
  EXPECT_GE(server->status().rejected, 3u);
}

TEST_F(TcpSlave, ConnectionsAreBoundedAndIdleOnesClosed) {
  TearDown();
  client = nullptr;
  start(/*max_conn=*/2, /*idle_ms=*/300);
  modbus_t* second = connect_client();
  uint16_t r[1];
  ASSERT_EQ(modbus_read_registers(second, 0, 1, r), 1);
  // A third is accepted and closed at once.
  const int third = raw_socket();
  uint8_t buf[16];
  EXPECT_EQ(read_reply(third, buf, sizeof buf), 0);
  close(third);
  // Silent connections are closed by the idle timeout (EOF within the 5 s bound)...
  EXPECT_EQ(read_reply(modbus_get_socket(second), buf, sizeof buf), 0);
  EXPECT_EQ(read_reply(modbus_get_socket(client), buf, sizeof buf), 0);
  modbus_close(second);
  modbus_free(second);
  modbus_close(client);
  modbus_free(client);
  // ... which frees their slots.
  client = connect_client();
  ASSERT_EQ(modbus_read_registers(client, 0, 1, r), 1);
}

}  // namespace
}  // namespace modbus
}  // namespace plc_cell
