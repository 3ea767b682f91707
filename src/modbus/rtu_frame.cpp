#include "plc_cell/modbus/rtu_frame.h"

#include <cstring>

namespace plc_cell {
namespace modbus {

namespace {
constexpr size_t kMaxAdu = 256;

bool crc_ok(const uint8_t* p, size_t n) {
  return n >= 4 && crc16(p, n - 2) == uint16_t(p[n - 2] | p[n - 1] << 8);
}

// Length of a request of a function code we serve, from its own fields; 0 when
// the code is another one or the fields are not there yet.
size_t request_length(const std::vector<uint8_t>& b) {
  if (b.size() < 2) return 0;
  switch (b[1]) {
    case 1: case 2: case 3: case 4: case 5: case 6: return 8;
    case 15: case 16: return b.size() >= 7 ? 9 + b[6] : 0;
    case 23: return b.size() >= 11 ? 13 + b[10] : 0;
    default: return 0;
  }
}
}  // namespace

uint16_t crc16(const uint8_t* p, size_t n) {
  uint16_t crc = 0xFFFF;
  for (size_t i = 0; i < n; ++i) {
    crc ^= p[i];
    for (int k = 0; k < 8; ++k) crc = (crc & 1) ? uint16_t((crc >> 1) ^ 0xA001) : uint16_t(crc >> 1);
  }
  return crc;
}

int rtu_adu(uint8_t slave, const uint8_t* pdu, int pdu_len, uint8_t* out) {
  out[0] = slave;
  std::memcpy(out + 1, pdu, size_t(pdu_len));
  int n = 1 + pdu_len;
  const uint16_t crc = crc16(out, size_t(n));
  out[n++] = uint8_t(crc & 0xFF);
  out[n++] = uint8_t(crc >> 8);
  return n;
}

int64_t t35_us(int baud) {
  if (baud <= 0 || baud > 19200) return 1750;
  return (35LL * 11 * 1000000) / (10LL * baud) + 1;
}

void RtuFramer::feed(const uint8_t* p, size_t n, int64_t now_us) {
  // A gap of t3.5 ends the previous frame even if poll() was not called in between.
  if (!buf_.empty() && now_us - last_rx_us_ >= garbage_us_) {
    garbage_ += buf_.size();
    buf_.clear();
  }
  buf_.insert(buf_.end(), p, p + n);
  last_rx_us_ = now_us;
}

RtuFramer::Event RtuFramer::poll(int64_t now_us) {
  if (buf_.empty()) return Event::None;
  const size_t want = request_length(buf_);
  if (want && buf_.size() >= want && crc_ok(buf_.data(), want)) {
    frame_.assign(buf_.begin(), buf_.begin() + long(want));
    buf_.erase(buf_.begin(), buf_.begin() + long(want));
    return Event::Frame;
  }
  const int64_t quiet = now_us - last_rx_us_;
  if (quiet >= silence_us_ && buf_.size() <= kMaxAdu) {
    // Silence ends the frame: any function code, as long as the CRC holds. After
    // line noise the frame is the tail whose CRC holds (the longest one).
    for (size_t start = 0; start + 4 <= buf_.size(); ++start) {
      if (!crc_ok(buf_.data() + start, buf_.size() - start)) continue;
      garbage_ += start;
      frame_.assign(buf_.begin() + long(start), buf_.end());
      buf_.clear();
      return Event::Frame;
    }
  }
  if (quiet >= garbage_us_ || buf_.size() > 2 * kMaxAdu) {
    garbage_ += buf_.size();
    buf_.clear();
    return Event::Garbage;
  }
  return Event::None;
}

int64_t RtuFramer::deadline_us(int64_t now_us) const {
  if (buf_.empty()) return -1;
  if (buf_.size() <= kMaxAdu && now_us < last_rx_us_ + silence_us_) return last_rx_us_ + silence_us_;
  return last_rx_us_ + garbage_us_;
}

}  // namespace modbus
}  // namespace plc_cell
