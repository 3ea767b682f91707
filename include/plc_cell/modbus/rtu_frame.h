#pragma once
// Modbus RTU framing for a slave: where one request ends on a serial line.
//
// Why not libmodbus's modbus_receive: it sizes a request by its function code and
// knows only the codes it implements, so a request with any other code (08
// diagnostics, 20 file record, 43 device identification, ...) is never framed: the
// slave stays silent instead of answering exception 01, and the bytes that follow
// are misread. The rules here are the serial line specification's: a frame ends
// at a silence of 3.5 characters; for the function codes we serve, the length
// their fields give ends it at once, so no silence has to be waited for.
// libmodbus still opens and configures the line (modbus_new_rtu, modbus_connect).
#include <cstddef>
#include <cstdint>
#include <vector>

namespace plc_cell {
namespace modbus {

// CRC-16/MODBUS of n bytes (polynomial A001H reflected, initial FFFFH). On the
// wire the low byte goes first.
uint16_t crc16(const uint8_t* p, size_t n);

// Slave id + PDU + CRC into out (room for 256 bytes); returns the ADU length.
int rtu_adu(uint8_t slave, const uint8_t* pdu, int pdu_len, uint8_t* out);

// The silence that ends a frame at this baud rate, in microseconds: 3.5 characters
// of 11 bits, and 1750 us above 19200 baud (the specification's fixed value).
int64_t t35_us(int baud);

class RtuFramer {
 public:
  // silence_us: t3.5 (or longer on a line with jitter, such as a pty relay).
  // garbage_us: silence after which bytes that make no valid frame are dropped.
  RtuFramer(int64_t silence_us, int64_t garbage_us) : silence_us_(silence_us), garbage_us_(garbage_us) {}

  enum class Event { None, Frame, Garbage };

  // Bytes arrived at now_us.
  void feed(const uint8_t* p, size_t n, int64_t now_us);
  // The next complete frame, or a garbage run to count; call until it returns None.
  // A frame is left in frame() (slave id .. CRC, CRC checked).
  Event poll(int64_t now_us);
  const std::vector<uint8_t>& frame() const { return frame_; }
  size_t garbage_bytes() const { return garbage_; }
  // When poll() next has something to say without new bytes; -1: never.
  int64_t deadline_us(int64_t now_us) const;
  bool in_frame() const { return !buf_.empty(); }
  void reset() { buf_.clear(); }

 private:
  std::vector<uint8_t> buf_;
  std::vector<uint8_t> frame_;
  size_t garbage_ = 0;
  int64_t last_rx_us_ = 0;
  int64_t silence_us_, garbage_us_;
};

}  // namespace modbus
}  // namespace plc_cell
