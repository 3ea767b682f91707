#include "plc_cell/tri/frame.h"

#include <cstdio>

#include "plc_cell/tri/fcs.h"
#include "hex_digit.h"

namespace plc_cell {
namespace tri {
namespace {

int hex2(std::string_view s) {
  if (s.size() != 2) return -1;
  const int a = hex_digit(s[0]), b = hex_digit(s[1]);
  return a < 0 || b < 0 ? -1 : a * 16 + b;
}

void report(const Decoder::Sink& sink, Decoder::Event::Kind kind, Fault fault = Fault::Garbage) {
  Decoder::Event ev;
  ev.kind = kind;
  ev.fault = fault;
  sink(ev);
}

}  // namespace

const char* fault_name(Fault f) {
  switch (f) {
    case Fault::NoTerminator: return "no '*' before CR";
    case Fault::TooLong: return "frame too long";
    case Fault::BadId: return "bad device ID";
    case Fault::BadFcs: return "FCS mismatch";
    case Fault::Garbage: return "garbage outside a frame";
  }
  return "?";
}

std::string encode_frame(const Frame& f) {
  std::string s;
  if (f.multipoint) {
    char id[3];
    std::snprintf(id, sizeof id, "%02X", unsigned(f.id & 0xFF));
    s = std::string("@") + id + f.body;
    s += fcs_hex(s);
  } else {
    s = f.body;
  }
  s += "*\r";
  return s;
}

bool parse_frame(std::string_view line, bool wildcard, Frame* out, bool* fcs_ok, Fault* fault) {
  *fcs_ok = true;
  if (line.empty() || line.back() != '*') {
    *fault = Fault::NoTerminator;
    return false;
  }
  line.remove_suffix(1);
  Frame f;
  if (line.front() != '@') {
    f.body = std::string(line);
    *out = std::move(f);
    return true;
  }
  f.multipoint = true;
  f.id = line.size() >= 3 ? hex2(line.substr(1, 2)) : -1;
  if (f.id < 0) {
    *fault = Fault::BadId;
    return false;
  }
  if (line.size() < 5) {  // '@', ID, FCS: no header at all
    *fault = Fault::BadFcs;
    return false;
  }
  const std::string_view covered = line.substr(0, line.size() - 2);
  const int sent = hex2(line.substr(line.size() - 2));
  f.body = std::string(covered.substr(3));
  if (sent < 0) {
    *fault = Fault::BadFcs;
    return false;
  }
  if (sent == 0 && wildcard) f.wildcard_fcs = fcs(covered) != 0;
  else *fcs_ok = sent == fcs(covered);
  *out = std::move(f);
  return true;
}

void Decoder::finish(const Sink& sink) {
  Event ev;
  Fault fault;
  if (parse_frame(line_, wildcard_, &ev.frame, &ev.fcs_ok, &fault)) {
    ev.kind = Event::FrameReady;
  } else {
    ev.kind = Event::Error;
    ev.fault = fault;
  }
  line_.clear();
  sink(ev);
}

void Decoder::feed(const uint8_t* data, size_t n, const Sink& sink) {
  for (size_t i = 0; i < n; ++i) {
    const char c = char(data[i]);
    if (c == '\r') {
      if (skipping_) skipping_ = false;
      else if (!line_.empty()) finish(sink);
      garbage_ = false;
      continue;
    }
    if (skipping_) continue;
    if (line_.empty()) {
      if (c == kEnq) {
        garbage_ = false;
        report(sink, Event::Enquiry);
        continue;
      }
      if (uint8_t(c) < 0x20 || uint8_t(c) >= 0x7F) {
        if (c != '\n' && !garbage_) {
          garbage_ = true;
          report(sink, Event::Error, Fault::Garbage);
        }
        continue;
      }
      garbage_ = false;
    }
    if (line_.size() >= kMaxFrame) {
      line_.clear();
      skipping_ = true;
      report(sink, Event::Error, Fault::TooLong);
      continue;
    }
    line_ += c;
  }
}

}  // namespace tri
}  // namespace plc_cell
