#include "plc_cell/fatek/protocol.h"

#include <cstring>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace fatek {
namespace {

struct WirePrefix {
  const char* text;
  Area area;
  Width width;
  int digits;
};

// Longest first, so that DWM beats D and DR beats D (spec 1.7 widths: 5/6/7 chars).
const WirePrefix kWire[] = {
    {"DWX", Area::X, Width::DWord, 4}, {"DWY", Area::Y, Width::DWord, 4}, {"DWM", Area::M, Width::DWord, 4},
    {"DWS", Area::S, Width::DWord, 4}, {"DWT", Area::T, Width::DWord, 4}, {"DWC", Area::C, Width::DWord, 4},
    {"DRT", Area::RT, Width::DWord, 4}, {"DRC", Area::RC, Width::DWord, 4}, {"DR", Area::R, Width::DWord, 5},
    {"DD", Area::D, Width::DWord, 5},  {"DF", Area::F, Width::DWord, 5},  {"WX", Area::X, Width::Word, 4},
    {"WY", Area::Y, Width::Word, 4},   {"WM", Area::M, Width::Word, 4},   {"WS", Area::S, Width::Word, 4},
    {"WT", Area::T, Width::Word, 4},   {"WC", Area::C, Width::Word, 4},   {"RT", Area::RT, Width::Word, 4},
    {"RC", Area::RC, Width::Word, 4},  {"X", Area::X, Width::Bit, 4},     {"Y", Area::Y, Width::Bit, 4},
    {"M", Area::M, Width::Bit, 4},     {"S", Area::S, Width::Bit, 4},     {"T", Area::T, Width::Bit, 4},
    {"C", Area::C, Width::Bit, 4},     {"R", Area::R, Width::Word, 5},    {"D", Area::D, Width::Word, 5},
    {"F", Area::F, Width::Word, 5},
};

bool span_fits(const Address& a, uint32_t count) {
  try {
    check_span(a, count);
    return true;
  } catch (const Error&) {
    return false;
  }
}

bool is_read(Cmd c) {
  return c == Cmd::ReadEnable || c == Cmd::ReadDiscretes || c == Cmd::ReadRegisters || c == Cmd::MixedRead;
}

void append_value(std::string& out, const Address& a, uint32_t v) {
  if (a.width == Width::Bit) out.push_back(v ? '1' : '0');
  else append_hex(out, v, a.width == Width::Word ? 4 : 8);
}

// Parses one value of a's width at s; Format on bad chars, IllegalValue on a discrete not 0/1.
ErrorCode parse_value(std::string_view s, const Address& a, uint32_t* v) {
  if (a.width == Width::Bit) {
    if (s.empty()) return ErrorCode::Format;
    if (s[0] != '0' && s[0] != '1') return ErrorCode::IllegalValue;
    *v = uint32_t(s[0] - '0');
    return ErrorCode::Ok;
  }
  return parse_hex(s, value_chars(a), v) ? ErrorCode::Ok : ErrorCode::Format;
}

uint32_t max_items(const Address& a) {
  if (a.width == Width::Bit) return kMaxDiscretes;
  return a.width == Width::Word ? kMaxWords : kMaxDWords;
}

}  // namespace

const char* error_text(ErrorCode e) {
  switch (e) {
    case ErrorCode::Ok: return "error free";
    case ErrorCode::IllegalValue: return "illegal value";
    case ErrorCode::Format: return "illegal format, or communication command can not execute";
    case ErrorCode::LadderChecksum: return "can not run (ladder checksum error)";
    case ErrorCode::IdMismatch: return "can not run (PLC ID differs from ladder ID)";
    case ErrorCode::Syntax: return "can not run (syntax check error)";
    case ErrorCode::NotSupported: return "can not run (function not supported)";
    case ErrorCode::IllegalAddress: return "illegal address";
  }
  return "unknown error";
}

bool is_error_code(char c) {
  switch (c) {
    case '0': case '2': case '4': case '5': case '6': case '7': case '9': case 'A': return true;
    default: return false;
  }
}

uint32_t weight(const Address& a) { return a.width == Width::DWord ? 2 : 1; }
int value_chars(const Address& a) { return a.width == Width::Bit ? 1 : a.width == Width::Word ? 4 : 8; }

std::string wire_address(const Address& a) { return format_fatek_address(a); }

ErrorCode parse_wire_address(std::string_view s, Address* out, size_t* used) {
  for (const auto& p : kWire) {
    const size_t plen = std::strlen(p.text);
    if (s.compare(0, plen, p.text) != 0) continue;
    if (s.size() < plen + size_t(p.digits)) return ErrorCode::Format;
    uint32_t n = 0;
    for (int i = 0; i < p.digits; ++i) {
      const char c = s[plen + i];
      if (c < '0' || c > '9') return ErrorCode::Format;
      n = n * 10 + uint32_t(c - '0');
    }
    const Address a{p.area, p.width, n};
    *used = plen + size_t(p.digits);
    if (!span_fits(a, 1)) return ErrorCode::IllegalAddress;
    *out = a;
    return ErrorCode::Ok;
  }
  return ErrorCode::Format;
}

// ---- master side -------------------------------------------------------------

void check_request(const Request& r) {
  auto fail = [&](const std::string& why) {
    char cmd[8];
    std::snprintf(cmd, sizeof cmd, "%02X", unsigned(r.cmd));
    throw Error(std::string("FATEK command ") + cmd + ": " + why);
  };
  auto check_start = [&](bool want_bit) {
    if (want_bit != (r.start.width == Width::Bit))
      fail(want_bit ? "needs a discrete address (X, Y, M, S, T, C)"
                    : "needs a register address (R, D, F, RT, RC, W or DW view)");
    if (r.count < 1 || r.count > max_items(r.start))
      fail("count " + std::to_string(r.count) + " outside 1.." + std::to_string(max_items(r.start)));
    check_span(r.start, r.count);
  };
  switch (r.cmd) {
    case Cmd::GistStatus:
    case Cmd::DetailedStatus:
    case Cmd::RunStop: break;
    case Cmd::Control:
      if (r.start.width != Width::Bit) fail("needs a discrete address");
      check_span(r.start, 1);
      break;
    case Cmd::ReadEnable:
    case Cmd::ReadDiscretes: check_start(true); break;
    case Cmd::WriteDiscretes:
      check_start(true);
      if (r.values.size() != r.count) fail("value count differs from count");
      for (uint32_t v : r.values)
        if (v > 1) fail("a discrete value must be 0 or 1");
      break;
    case Cmd::ReadRegisters: check_start(false); break;
    case Cmd::WriteRegisters:
      check_start(false);
      if (r.values.size() != r.count) fail("value count differs from count");
      for (uint32_t v : r.values)
        if (r.start.width == Width::Word && v > 0xFFFF) fail("value does not fit 16 bits");
      break;
    case Cmd::MixedRead:
    case Cmd::MixedWrite: {
      const bool write = r.cmd == Cmd::MixedWrite;
      if (r.points.empty()) fail("no points");
      if (write && r.values.size() != r.points.size()) fail("value count differs from point count");
      uint32_t w = 0;
      for (size_t i = 0; i < r.points.size(); ++i) {
        check_span(r.points[i], 1);
        w += weight(r.points[i]);
        if (write) {
          const Address& a = r.points[i];
          const uint32_t v = r.values[i];
          if ((a.width == Width::Bit && v > 1) || (a.width == Width::Word && v > 0xFFFF))
            fail("value for " + format_address(a) + " does not fit");
        }
      }
      const uint32_t limit = write ? kMaxMixedWriteWeight : kMaxMixedReadWeight;
      if (w > limit) fail("weight " + std::to_string(w) + " exceeds " + std::to_string(limit));
      break;
    }
    case Cmd::Loopback:
      if (r.text.size() > kMaxLoopback) fail("loop-back text longer than 256 chars");
      for (char c : r.text)
        if (c < 0x20 || c > 0x7E) fail("loop-back text must be printable ASCII");
      break;
    default: fail("unknown command");
  }
}

std::string encode_request(const Request& r) {
  check_request(r);
  std::string d;
  switch (r.cmd) {
    case Cmd::RunStop: d.push_back(r.run ? '1' : '0'); break;
    case Cmd::Control:
      d.push_back(char('0' + uint8_t(r.action)));
      d += wire_address(r.start);
      break;
    case Cmd::ReadEnable:
    case Cmd::ReadDiscretes:
    case Cmd::ReadRegisters:
    case Cmd::WriteDiscretes:
    case Cmd::WriteRegisters:
      append_hex(d, r.count & 0xFF, 2);  // 256 is sent as 00
      d += wire_address(r.start);
      if (r.cmd == Cmd::WriteDiscretes || r.cmd == Cmd::WriteRegisters)
        for (uint32_t v : r.values) append_value(d, r.start, v);
      break;
    case Cmd::MixedRead:
    case Cmd::MixedWrite:
      append_hex(d, uint32_t(r.points.size()), 2);
      for (size_t i = 0; i < r.points.size(); ++i) {
        d += wire_address(r.points[i]);
        if (r.cmd == Cmd::MixedWrite) append_value(d, r.points[i], r.values[i]);
      }
      break;
    case Cmd::Loopback: d = r.text; break;
    default: break;
  }
  std::string out;
  append_frame(out, r.station, uint8_t(r.cmd), d);
  return out;
}

bool parse_response(const Request& req, const Frame& f, Response* out, std::string* why) {
  auto bad = [&](const std::string& w) {
    *why = w;
    return false;
  };
  if (f.command != uint8_t(req.cmd)) return bad("response to another command");
  if (f.station != req.station) return bad("response from station " + std::to_string(f.station));
  out->station = f.station;
  out->cmd = req.cmd;
  out->values.clear();
  out->status.clear();
  out->text.clear();
  out->error = ErrorCode::Ok;
  if (req.cmd == Cmd::Loopback) {  // verbatim echo without an error char (spec 5.2)
    if (f.data != req.text) return bad("loop-back echo differs from the request");
    out->text = f.data;
    return true;
  }
  if (f.data.empty() || !is_error_code(f.data[0])) return bad("missing or unknown error code");
  out->error = ErrorCode(f.data[0]);
  std::string_view d(f.data);
  d.remove_prefix(1);
  if (out->error != ErrorCode::Ok) return d.empty() ? true : bad("error response with data");
  auto values_of = [&](const Address& a, uint32_t n) -> bool {
    const size_t w = size_t(value_chars(a));
    if (d.size() < w * n) return false;
    const size_t first = out->values.size();
    out->values.resize(first + n);
    uint32_t* dst = out->values.data() + first;
    const char* p = d.data();
    for (uint32_t i = 0; i < n; ++i, p += w) {
      if (w == 1) {
        if (*p != '0' && *p != '1') return false;
        dst[i] = uint32_t(*p - '0');
        continue;
      }
      uint32_t v = 0;
      int bad = 0;
      for (size_t k = 0; k < w; ++k) {
        const int h = hex_value(p[k]);
        bad |= h;  // any -1 sets the sign bit
        v = (v << 4) | uint32_t(h & 0xF);
      }
      if (bad < 0) return false;
      dst[i] = v;
    }
    d.remove_prefix(w * n);
    return true;
  };
  switch (req.cmd) {
    case Cmd::GistStatus:
    case Cmd::DetailedStatus: {
      if (d.size() % 2 || d.empty()) return bad("status bytes are not whole");
      while (!d.empty()) {
        uint32_t b;
        if (!parse_hex(d, 2, &b)) return bad("non-hex status byte");
        out->status.push_back(uint8_t(b));
        d.remove_prefix(2);
      }
      if (req.cmd == Cmd::GistStatus && out->status.size() != 3) return bad("cmd 40 carries 3 status bytes");
      return true;
    }
    case Cmd::ReadEnable:
    case Cmd::ReadDiscretes:
    case Cmd::ReadRegisters:
      if (!values_of(req.start, req.count)) return bad("short or malformed values");
      break;
    case Cmd::MixedRead:
      for (const auto& p : req.points)
        if (!values_of(p, 1)) return bad("short or malformed values");
      break;
    default: break;
  }
  if (!d.empty()) return bad("unexpected trailing data");
  return true;
}

// ---- slave side --------------------------------------------------------------

namespace {

// The parts of a request's data, consumed from the front of d.
ErrorCode parse_start_and_count(std::string_view& d, bool want_bit, Request* r) {
  uint32_t n;
  if (!parse_hex(d, 2, &n)) return ErrorCode::Format;
  size_t used = 0;
  const ErrorCode e = parse_wire_address(d.substr(2), &r->start, &used);
  if (e != ErrorCode::Ok) return e;
  d.remove_prefix(2 + used);
  if (want_bit != (r->start.width == Width::Bit)) return ErrorCode::Format;
  if (want_bit && n == 0) n = 256;
  if (n == 0 || n > max_items(r->start)) return ErrorCode::IllegalValue;
  r->count = n;
  if (!span_fits(r->start, n)) return ErrorCode::IllegalAddress;
  return ErrorCode::Ok;
}

ErrorCode parse_values(std::string_view d, Request* r) {
  const size_t w = size_t(value_chars(r->start));
  if (d.size() != w * r->count) return ErrorCode::Format;
  for (uint32_t i = 0; i < r->count; ++i) {
    uint32_t v;
    const ErrorCode e = parse_value(d.substr(i * w), r->start, &v);
    if (e != ErrorCode::Ok) return e;
    r->values.push_back(v);
  }
  return ErrorCode::Ok;
}

ErrorCode parse_control(std::string_view d, Request* r) {
  if (d.size() != 6) return ErrorCode::Format;
  if (d[0] < '1' || d[0] > '4') return ErrorCode::IllegalValue;
  r->action = Action(d[0] - '0');
  size_t used = 0;
  const ErrorCode e = parse_wire_address(d.substr(1), &r->start, &used);
  if (e != ErrorCode::Ok) return e;
  return r->start.width == Width::Bit ? ErrorCode::Ok : ErrorCode::Format;
}

// Commands 48 and 49: a count, then that many addresses (each with its value for 49).
ErrorCode parse_mixed(std::string_view d, bool write, Request* r) {
  uint32_t n;
  if (!parse_hex(d, 2, &n)) return ErrorCode::Format;
  d.remove_prefix(2);
  if (n == 0 || n > (write ? kMaxMixedWriteWeight : kMaxMixedReadWeight)) return ErrorCode::IllegalValue;
  uint32_t w = 0;
  for (uint32_t i = 0; i < n; ++i) {
    Address a;
    size_t used = 0;
    const ErrorCode e = parse_wire_address(d, &a, &used);
    if (e != ErrorCode::Ok) return e;
    d.remove_prefix(used);
    r->points.push_back(a);
    w += weight(a);
    if (write) {
      uint32_t v;
      const ErrorCode ev = parse_value(d, a, &v);
      if (ev != ErrorCode::Ok) return ev;
      d.remove_prefix(size_t(value_chars(a)));
      r->values.push_back(v);
    }
  }
  if (w > (write ? kMaxMixedWriteWeight : kMaxMixedReadWeight)) return ErrorCode::IllegalValue;
  return d.empty() ? ErrorCode::Ok : ErrorCode::Format;
}

}  // namespace

ErrorCode parse_request(const Frame& f, Request* r) {
  r->station = f.station;
  r->cmd = Cmd(f.command);
  r->values.clear();
  r->points.clear();
  r->text.clear();
  r->count = 0;
  std::string_view d(f.data);
  switch (r->cmd) {
    case Cmd::GistStatus:
    case Cmd::DetailedStatus: return d.empty() ? ErrorCode::Ok : ErrorCode::Format;
    case Cmd::RunStop:
      if (d.size() != 1) return ErrorCode::Format;
      if (d[0] != '0' && d[0] != '1') return ErrorCode::IllegalValue;
      r->run = d[0] == '1';
      return ErrorCode::Ok;
    case Cmd::Control: return parse_control(d, r);
    case Cmd::ReadEnable:
    case Cmd::ReadDiscretes:
    case Cmd::ReadRegisters: {
      const ErrorCode e = parse_start_and_count(d, r->cmd != Cmd::ReadRegisters, r);
      if (e != ErrorCode::Ok) return e;
      return d.empty() ? ErrorCode::Ok : ErrorCode::Format;
    }
    case Cmd::WriteDiscretes:
    case Cmd::WriteRegisters: {
      const ErrorCode e = parse_start_and_count(d, r->cmd == Cmd::WriteDiscretes, r);
      return e != ErrorCode::Ok ? e : parse_values(d, r);
    }
    case Cmd::MixedRead:
    case Cmd::MixedWrite: return parse_mixed(d, r->cmd == Cmd::MixedWrite, r);
    case Cmd::Loopback:
      if (d.size() > kMaxLoopback) return ErrorCode::Format;
      r->text.assign(d.data(), d.size());
      return ErrorCode::Ok;
  }
  return ErrorCode::Format;  // unknown command code
}

void append_response(std::string& out, const Request& req, const Response& r) {
  // Built in place (no temporary): STX, station, command, data, then the LRC over them.
  const size_t start = out.size();
  out.push_back(char(kStx));
  append_hex(out, r.station, 2);
  append_hex(out, uint8_t(req.cmd), 2);
  if (req.cmd == Cmd::Loopback && r.error == ErrorCode::Ok) {
    out += r.text;
  } else {
    out.push_back(char(r.error));
    if (r.error == ErrorCode::Ok) {
      for (uint8_t b : r.status) append_hex(out, b, 2);
      if (req.cmd == Cmd::MixedRead) {
        for (size_t i = 0; i < r.values.size() && i < req.points.size(); ++i) append_value(out, req.points[i], r.values[i]);
      } else if (is_read(req.cmd)) {
        // Hot path (46 x 64): size once, then write the hex digits in place.
        const size_t w = size_t(value_chars(req.start));
        size_t at = out.size();
        out.resize(at + w * r.values.size());
        char* p = &out[0];
        for (uint32_t v : r.values) {
          if (w == 1) {
            p[at++] = v ? '1' : '0';
            continue;
          }
          for (size_t k = w; k-- > 0; v >>= 4) p[at + k] = "0123456789ABCDEF"[v & 0xF];
          at += w;
        }
      }
    }
  }
  if (out.size() - start - 5 > kMaxData) {
    out.resize(start);
    throw Error("FATEK response data exceeds 500 chars");
  }
  append_hex(out, lrc(std::string_view(out).substr(start)), 2);
  out.push_back(char(kEtx));
}

std::string encode_response(const Request& req, const Response& r) {
  std::string out;
  out.reserve(kMaxFrame);
  append_response(out, req, r);
  return out;
}

}  // namespace fatek
}  // namespace plc_cell
