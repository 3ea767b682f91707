#pragma once
// TRi host-link framing (manual chapter 15). Two forms share one terminator, '*' CR:
//   point-to-point  HEADER data * CR          (after the Ctrl-E handshake, 0x05 echoed)
//   multi-point     @ ID HEADER data FCS * CR (ID and FCS: 2 hex digits each)
// A Frame holds the text between the framing: the header and its data together
// (`body`), since headers are 2 or 3 characters and commands.h tells them apart.
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

namespace plc_cell {
namespace tri {

constexpr char kEnq = 0x05;       // Ctrl-E: a point-to-point session starts; echoed
constexpr size_t kMaxFrame = 256; // longest frame taken, '@' to CR (a 70-character string fits)

struct Frame {
  bool multipoint = false;
  int id = 0;              // multi-point only: 0..255
  std::string body;        // header and data, e.g. "RVD0E10"
  bool wildcard_fcs = false;  // multi-point frame sent with FCS "00" instead of its own
};

// The bytes of f: "RVD0E10*\r" or "@04RVIA48*\r" (its own FCS; never the wildcard).
std::string encode_frame(const Frame& f);

enum class Fault {
  NoTerminator,  // a line ended by CR without the '*' before it
  TooLong,       // more than kMaxFrame characters before the CR
  BadId,         // '@' not followed by 2 hex digits
  BadFcs,        // multi-point FCS not 2 hex digits, or not the frame's (see Decoder::Event)
  Garbage,       // control characters outside a frame
};
const char* fault_name(Fault f);

// Streaming decoder for a byte stream (a serial line, a TCP connection). Bytes may come
// one at a time or many frames at once. Ctrl-E outside a frame is reported at once;
// LF and other control characters outside a frame are dropped (Garbage, once per run);
// any printable character starts a frame, which ends at CR. A frame whose multi-point
// FCS does not match is still delivered, with fcs_ok false, so that the slave can send
// its framing-error response to the right ID.
class Decoder {
 public:
  struct Event {
    enum Kind { Enquiry, FrameReady, Error } kind = FrameReady;
    Frame frame;          // FrameReady
    bool fcs_ok = true;   // FrameReady, multi-point: false when the FCS does not match
    Fault fault = Fault::Garbage;  // Error
  };
  using Sink = std::function<void(const Event&)>;

  // wildcard: accept FCS "00" on any frame (AUTO mode; SETPROTOCOL n,5 refuses it).
  explicit Decoder(bool wildcard = true) : wildcard_(wildcard) {}
  void feed(const uint8_t* data, size_t n, const Sink& sink);
  void feed(std::string_view s, const Sink& sink) {
    feed(reinterpret_cast<const uint8_t*>(s.data()), s.size(), sink);
  }
  bool in_frame() const { return !line_.empty() || skipping_; }
  // The line went quiet mid-frame: drop it.
  void reset() {
    line_.clear();
    skipping_ = false;
  }

 private:
  void finish(const Sink& sink);
  bool wildcard_;
  std::string line_;
  bool skipping_ = false;  // after TooLong, until the next CR
  bool garbage_ = false;   // a run of garbage already reported
};

// One frame parsed from a whole line (without the CR), as the Decoder does.
// Returns false and sets *fault when it is not a frame.
bool parse_frame(std::string_view line, bool wildcard, Frame* out, bool* fcs_ok, Fault* fault);

}  // namespace tri
}  // namespace plc_cell
