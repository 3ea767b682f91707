#include "plc_cell/tri/commands.h"
#include "hex_digit.h"

#include <cstdio>

namespace plc_cell {
namespace tri {
namespace {

// A layout is one character per field, in order (see commands.h for the headers):
//   a  2 hex -> Request::a      A  4 hex -> a       n  1 hex -> a      v  letter A-Z -> a (0-25)
//   b  2 hex -> b               x  2 hex -> value   w  4 hex -> value  L  8 hex -> value
//   d  4 decimal -> value       f  FF/00 -> value 1/0
//   *  4-hex words to the end -> values (a request's count is b)     t  text to the end
struct Layout {
  Cmd cmd;
  const char* header;
  const char* request;
  const char* response;
};

constexpr Layout kLayouts[] = {
    {Cmd::ReadId, "IR", "", "x"},
    {Cmd::WriteId, "IW", "a", ""},
    {Cmd::ReadInputs, "RI", "a", "x"},
    {Cmd::ReadOutputs, "RO", "a", "x"},
    {Cmd::ReadRelays, "RR", "a", "x"},
    {Cmd::ReadTimerBits, "RT", "a", "x"},
    {Cmd::ReadCounterBits, "RC", "a", "x"},
    {Cmd::ReadTimerPv, "RM", "a", "d"},
    {Cmd::ReadTimerSv, "Rm", "a", "d"},
    {Cmd::ReadCounterPv, "RU", "a", "d"},
    {Cmd::ReadCounterSv, "Ru", "a", "d"},
    {Cmd::ReadInteger, "RVI", "v", "L"},
    {Cmd::ReadString, "RV$", "v", "t"},
    {Cmd::ReadDm, "RVD", "A", "w"},
    {Cmd::ReadSystem, "RVS", "ab", "w"},
    {Cmd::ReadHsc, "RVH", "n", "L"},
    {Cmd::WriteInputs, "WI", "ax", ""},
    {Cmd::WriteOutputs, "WO", "ax", ""},
    {Cmd::WriteRelays, "WR", "ax", ""},
    {Cmd::WriteTimerBits, "WT", "ax", ""},
    {Cmd::WriteCounterBits, "WC", "ax", ""},
    {Cmd::WriteTimerPv, "WM", "ad", ""},
    {Cmd::WriteTimerSv, "Wm", "ad", ""},
    {Cmd::WriteCounterPv, "WU", "ad", ""},
    {Cmd::WriteCounterSv, "Wu", "ad", ""},
    {Cmd::WriteInteger, "WVI", "vL", ""},
    {Cmd::WriteString, "WV$", "vt", ""},
    {Cmd::WriteDm, "WVD", "Aw", ""},
    {Cmd::WriteSystem, "WVS", "abw", ""},
    {Cmd::WriteHsc, "WVH", "nL", ""},
    {Cmd::ReadAnalog, "RA", "ab", "*"},
    {Cmd::WriteAnalog, "WA", "ab*", "x"},
    {Cmd::ReadEepromInts, "RXI", "Ab", "*"},
    {Cmd::ReadEepromString, "RX$", "A", "t"},
    {Cmd::WriteEepromInts, "WXI", "Ab*", ""},
    {Cmd::WriteEepromString, "WX$", "At", ""},
    {Cmd::ForceBit, "wb", "Af", ""},
    {Cmd::Halt, "C2", "", ""},
    {Cmd::Resume, "C3", "", ""},
};

// Other spellings the manual's own examples use.
struct Alias {
  const char* header;
  Cmd cmd;
};
constexpr Alias kAliases[] = {{"wvH", Cmd::WriteHsc}, {"Wb", Cmd::ForceBit}};

const Layout& layout(Cmd c) {
  for (const auto& l : kLayouts)
    if (l.cmd == c) return l;
  return kLayouts[0];
}

bool match_header(std::string_view body, Cmd* cmd, size_t* len) {
  for (size_t n : {size_t(3), size_t(2)}) {
    if (body.size() < n) continue;
    const std::string_view h = body.substr(0, n);
    for (const auto& l : kLayouts)
      if (h == l.header) {
        *cmd = l.cmd;
        *len = n;
        return true;
      }
    for (const auto& a : kAliases)
      if (h == a.header) {
        *cmd = a.cmd;
        *len = n;
        return true;
      }
  }
  return false;
}

// n hex digits from the front of s; false when there are not n of them.
bool take_hex(std::string_view& s, size_t n, uint32_t* v) {
  if (s.size() < n) return false;
  uint32_t x = 0;
  for (size_t i = 0; i < n; ++i) {
    const int d = hex_digit(s[i]);
    if (d < 0) return false;
    x = x << 4 | uint32_t(d);
  }
  s.remove_prefix(n);
  *v = x;
  return true;
}

bool take_decimal(std::string_view& s, uint32_t* v) {
  if (s.size() < 4) return false;
  uint32_t x = 0;
  for (size_t i = 0; i < 4; ++i) {
    if (s[i] < '0' || s[i] > '9') return false;
    x = x * 10 + uint32_t(s[i] - '0');
  }
  s.remove_prefix(4);
  *v = x;
  return true;
}

void put_hex(std::string& s, uint32_t v, int digits) {
  static const char* kHex = "0123456789ABCDEF";
  for (int i = digits - 1; i >= 0; --i) s += kHex[(v >> (4 * i)) & 15];
}

// Reads the fields of spec from data into the three places; count: b for '*'.
bool read_fields(const char* spec, std::string_view data, uint32_t* a, uint32_t* b, std::vector<uint32_t>* values,
                 std::string* text, bool request) {
  for (const char* p = spec; *p; ++p) {
    uint32_t v = 0;
    switch (*p) {
      case 'a': if (!take_hex(data, 2, a)) return false; break;
      case 'A': if (!take_hex(data, 4, a)) return false; break;
      case 'n': if (!take_hex(data, 1, a)) return false; break;
      case 'b': if (!take_hex(data, 2, b)) return false; break;
      case 'v':
        if (data.empty() || data[0] < 'A' || data[0] > 'Z') return false;
        *a = uint32_t(data[0] - 'A');
        data.remove_prefix(1);
        break;
      case 'x': if (!take_hex(data, 2, &v)) return false; values->push_back(v); break;
      case 'w': if (!take_hex(data, 4, &v)) return false; values->push_back(v); break;
      case 'L': if (!take_hex(data, 8, &v)) return false; values->push_back(v); break;
      case 'd': if (!take_decimal(data, &v)) return false; values->push_back(v); break;
      case 'f':
        if (!take_hex(data, 2, &v) || (v != 0xFF && v != 0)) return false;
        values->push_back(v ? 1 : 0);
        break;
      case '*':
        if (data.size() % 4) return false;
        if (request && data.size() / 4 != *b) return false;
        while (!data.empty()) {
          if (!take_hex(data, 4, &v)) return false;
          values->push_back(v);
        }
        break;
      case 't':
        *text = std::string(data);
        data = {};
        break;
    }
  }
  return data.empty();
}

void write_fields(const char* spec, std::string& s, uint32_t a, uint32_t b, const std::vector<uint32_t>& values,
                  const std::string& text) {
  size_t k = 0;
  auto next = [&] { return k < values.size() ? values[k++] : 0u; };
  for (const char* p = spec; *p; ++p) {
    switch (*p) {
      case 'a': put_hex(s, a, 2); break;
      case 'A': put_hex(s, a, 4); break;
      case 'n': put_hex(s, a, 1); break;
      case 'b': put_hex(s, b, 2); break;
      case 'v': s += char('A' + a % 26); break;
      case 'x': put_hex(s, next(), 2); break;
      case 'w': put_hex(s, next(), 4); break;
      case 'L': put_hex(s, next(), 8); break;
      case 'd': {
        char d[8];
        std::snprintf(d, sizeof d, "%04u", next() % 10000);
        s += d;
        break;
      }
      case 'f': s += next() ? "FF" : "00"; break;
      case '*':
        while (k < values.size()) put_hex(s, values[k++], 4);
        break;
      case 't': s += text; break;
    }
  }
}

}  // namespace

const char* error_name(ErrorCode e) {
  switch (e) {
    case ErrorCode::Ok: return "ok";
    case ErrorCode::UnknownCommand: return "unknown command";
    case ErrorCode::BadData: return "bad data";
    case ErrorCode::OutOfRange: return "out of range";
    case ErrorCode::NotWritable: return "not writable";
    case ErrorCode::CannotExecute: return "cannot execute";
  }
  return "?";
}

const char* header_of(Cmd c) { return layout(c).header; }

std::string encode_request(const Request& r) {
  std::string s = r.header.empty() ? header_of(r.cmd) : r.header;
  write_fields(layout(r.cmd).request, s, r.a, r.b, r.values, r.text);
  return s;
}

ErrorCode parse_request(std::string_view body, Request* out) {
  Request r;
  size_t n = 0;
  if (!match_header(body, &r.cmd, &n)) return ErrorCode::UnknownCommand;
  r.header = std::string(body.substr(0, n));
  if (!read_fields(layout(r.cmd).request, body.substr(n), &r.a, &r.b, &r.values, &r.text, true))
    return ErrorCode::BadData;
  *out = std::move(r);
  return ErrorCode::Ok;
}

std::string encode_response(const Request& req, const Response& rsp) {
  if (rsp.error != ErrorCode::Ok) {
    std::string s = "ER";
    put_hex(s, uint32_t(rsp.error), 2);
    return s;
  }
  std::string s = req.header.empty() ? header_of(req.cmd) : req.header;
  write_fields(layout(req.cmd).response, s, 0, 0, rsp.values, rsp.text);
  return s;
}

bool parse_response(const Request& req, std::string_view body, Response* rsp) {
  Response r;
  r.cmd = req.cmd;
  if (body.size() == 4 && body.substr(0, 2) == "ER") {
    std::string_view code = body.substr(2);
    uint32_t e = 0;
    if (!take_hex(code, 2, &e) || e == 0) return false;
    r.error = ErrorCode(e);
    *rsp = std::move(r);
    return true;
  }
  const std::string header = req.header.empty() ? header_of(req.cmd) : req.header;
  if (body.substr(0, header.size()) != header) return false;
  r.header = header;
  uint32_t a = 0, b = 0;
  if (!read_fields(layout(req.cmd).response, body.substr(header.size()), &a, &b, &r.values, &r.text, false))
    return false;
  *rsp = std::move(r);
  return true;
}

}  // namespace tri
}  // namespace plc_cell
