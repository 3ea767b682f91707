#pragma once
// FATEK frame layer: STX | station(2 hex) | command(2 hex) | data(0..500) | LRC(2 hex) | ETX.
// LRC = sum of every byte from STX through the last data byte, mod 256 (spec 1.4).
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace plc_cell {
namespace fatek {

constexpr uint8_t kStx = 0x02;
constexpr uint8_t kEtx = 0x03;
constexpr size_t kMaxData = 500;
constexpr size_t kMaxFrame = 1 + 2 + 2 + kMaxData + 2 + 1;  // 508
constexpr size_t kMinFrame = 1 + 2 + 2 + 2 + 1;             // 8: no data

struct Frame {
  uint8_t station = 0;
  uint8_t command = 0;
  std::string data;  // ASCII, without STX/LRC/ETX
};

uint8_t lrc(std::string_view bytes);
// Appends a complete frame to out. Throws plc_cell::Error if data exceeds 500 chars.
void append_frame(std::string& out, uint8_t station, uint8_t command, std::string_view data);
std::string encode_frame(const Frame& f);

// Hex helpers shared by the codec (upper-case out, either case in).
namespace detail {
struct HexTable {
  int8_t v[256];
  constexpr HexTable() : v() {
    for (int i = 0; i < 256; ++i) v[i] = -1;
    for (int i = 0; i < 10; ++i) v['0' + i] = int8_t(i);
    for (int i = 0; i < 6; ++i) v['A' + i] = v['a' + i] = int8_t(10 + i);
  }
};
inline constexpr HexTable kHexTable;
}  // namespace detail
// -1 if not a hex digit. Inline: the codec calls it for every character.
inline int hex_value(char c) { return detail::kHexTable.v[static_cast<unsigned char>(c)]; }
void append_hex(std::string& out, uint32_t v, int digits);
// Parses exactly `digits` hex chars at s; false on a non-hex char or short input.
bool parse_hex(std::string_view s, int digits, uint32_t* v);

// Streaming decoder with a fixed 508-byte buffer: never allocates beyond one frame.
// Bytes before STX are ignored; a new STX inside a frame restarts the frame (resync).
class Decoder {
 public:
  enum class Status { Incomplete, Frame, Error };
  enum class Fault { None, BadLrc, NonHex, Oversize, TooShort, BadByte, Truncated };

  // Consumes one byte. On Frame, frame() holds the decoded frame until the next push.
  Status push(uint8_t byte);
  // Feeds a buffer; calls on_frame(const Frame&) per good frame and on_error(Fault) per bad one.
  // Fast path: plain data bytes are copied in runs; STX, ETX and bad bytes go through push().
  template <typename OnFrame, typename OnError>
  void feed(const uint8_t* p, size_t n, OnFrame&& on_frame, OnError&& on_error) {
    size_t i = 0;
    while (i < n) {
      if (len_ > 0) {
        // Copy printable bytes (never STX/ETX) while there is room; linear in n.
        const size_t room = kMaxFrame - 1 - len_;
        size_t j = i;
        while (j < n && j - i < room && p[j] >= 0x20 && p[j] <= 0x7E) ++j;
        if (j > i) {
          std::memcpy(buf_.data() + len_, p + i, j - i);
          len_ += j - i;
          i = j;
          if (i == n) break;
        }
      }
      const Status s = push(p[i++]);
      if (s == Status::Frame) on_frame(frame_);
      else if (s == Status::Error) on_error(fault_);
    }
  }
  // The inter-byte timeout expired: a partial frame is dropped. Returns true if one was pending.
  bool timeout();
  bool in_frame() const { return len_ > 0; }
  const Frame& frame() const { return frame_; }
  Fault fault() const { return fault_; }
  void reset() { len_ = 0; }

 private:
  Status finish();
  std::array<uint8_t, kMaxFrame> buf_{};
  size_t len_ = 0;  // bytes stored, buf_[0] == STX when > 0
  Frame frame_;
  Fault fault_ = Fault::None;
};

const char* fault_name(Decoder::Fault f);

}  // namespace fatek
}  // namespace plc_cell
