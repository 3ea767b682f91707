#include "plc_cell/fatek/frame.h"

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace fatek {

static const char kHex[] = "0123456789ABCDEF";

uint8_t lrc(std::string_view bytes) {
  unsigned sum = 0;
  for (unsigned char c : bytes) sum += c;
  return static_cast<uint8_t>(sum & 0xFF);
}


void append_hex(std::string& out, uint32_t v, int digits) {
  char buf[8];
  for (int i = digits - 1; i >= 0; --i, v >>= 4) buf[i] = kHex[v & 0xF];
  out.append(buf, size_t(digits));
}

bool parse_hex(std::string_view s, int digits, uint32_t* v) {
  if (s.size() < static_cast<size_t>(digits)) return false;
  uint32_t r = 0;
  for (int i = 0; i < digits; ++i) {
    const int h = hex_value(s[i]);
    if (h < 0) return false;
    r = (r << 4) | uint32_t(h);
  }
  *v = r;
  return true;
}

void append_frame(std::string& out, uint8_t station, uint8_t command, std::string_view data) {
  if (data.size() > kMaxData)
    throw Error("FATEK frame data of " + std::to_string(data.size()) + " chars exceeds 500");
  const size_t start = out.size();
  out.push_back(char(kStx));
  append_hex(out, station, 2);
  append_hex(out, command, 2);
  out.append(data.data(), data.size());
  append_hex(out, lrc(std::string_view(out).substr(start)), 2);
  out.push_back(char(kEtx));
}

std::string encode_frame(const Frame& f) {
  std::string out;
  out.reserve(kMinFrame + f.data.size());
  append_frame(out, f.station, f.command, f.data);
  return out;
}

Decoder::Status Decoder::push(uint8_t b) {
  if (b == kStx) {  // start, or resync on a new STX inside a broken frame
    const bool lost = len_ > 0;
    len_ = 1;
    buf_[0] = b;
    if (lost) {
      fault_ = Fault::Truncated;
      return Status::Error;
    }
    return Status::Incomplete;
  }
  if (len_ == 0) return Status::Incomplete;  // garbage before STX (or the rest of an oversize frame)
  if (b == kEtx) return finish();
  if (b < 0x20 || b > 0x7E) {  // the protocol is printable ASCII only
    len_ = 0;
    fault_ = Fault::BadByte;
    return Status::Error;
  }
  if (len_ >= kMaxFrame - 1) {  // no room left for ETX
    len_ = 0;
    fault_ = Fault::Oversize;
    return Status::Error;
  }
  buf_[len_++] = b;
  return Status::Incomplete;
}

Decoder::Status Decoder::finish() {
  const size_t n = len_;
  len_ = 0;
  if (n + 1 < kMinFrame) {
    fault_ = Fault::TooShort;
    return Status::Error;
  }
  const std::string_view body(reinterpret_cast<const char*>(buf_.data()), n);
  uint32_t station, command, sum;
  if (!parse_hex(body.substr(1), 2, &station) || !parse_hex(body.substr(3), 2, &command) ||
      !parse_hex(body.substr(n - 2), 2, &sum)) {
    fault_ = Fault::NonHex;
    return Status::Error;
  }
  if (lrc(body.substr(0, n - 2)) != sum) {
    fault_ = Fault::BadLrc;
    return Status::Error;
  }
  frame_.station = uint8_t(station);
  frame_.command = uint8_t(command);
  frame_.data.assign(body.data() + 5, n - 7);  // capacity stays <= 500 after the first frames
  fault_ = Fault::None;
  return Status::Frame;
}

bool Decoder::timeout() {
  const bool pending = len_ > 0;
  len_ = 0;
  if (pending) fault_ = Fault::Truncated;
  return pending;
}

const char* fault_name(Decoder::Fault f) {
  switch (f) {
    case Decoder::Fault::None: return "none";
    case Decoder::Fault::BadLrc: return "bad LRC";
    case Decoder::Fault::NonHex: return "non-hex station, command or LRC";
    case Decoder::Fault::Oversize: return "frame longer than 508 bytes";
    case Decoder::Fault::TooShort: return "frame too short";
    case Decoder::Fault::BadByte: return "control byte inside a frame";
    case Decoder::Fault::Truncated: return "frame cut short";
  }
  return "?";
}

}  // namespace fatek
}  // namespace plc_cell
