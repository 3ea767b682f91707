#include "plc_cell/tri/slave.h"

#include <algorithm>
#include <functional>
#include <utility>
#include <vector>

#include "plc_cell/core/error.h"
#include "plc_cell/tri/fcs.h"
#include "plc_cell/tri/memory_map.h"

namespace plc_cell {
namespace tri {
namespace {

// What one request does to memory, worked out before the lock: the elements it reads,
// the elements it writes with their values, and how the values read become the response.
struct Plan {
  std::vector<Address> reads;
  std::vector<std::pair<Address, uint32_t>> writes;
  std::function<void(const std::vector<uint32_t>&, Response*)> finish;
};

bool channel_kind(Cmd c, BitKind* k) {
  switch (c) {
    case Cmd::ReadInputs: case Cmd::WriteInputs: *k = BitKind::Input; return true;
    case Cmd::ReadOutputs: case Cmd::WriteOutputs: *k = BitKind::Output; return true;
    case Cmd::ReadRelays: case Cmd::WriteRelays: *k = BitKind::Relay; return true;
    case Cmd::ReadTimerBits: case Cmd::WriteTimerBits: *k = BitKind::Timer; return true;
    case Cmd::ReadCounterBits: case Cmd::WriteCounterBits: *k = BitKind::Counter; return true;
    default: return false;
  }
}

// The 8 (or 16) discretes of a channel (or word): bit 0 = the lowest-numbered.
bool bits_of(BitKind k, uint32_t first, uint32_t n, std::vector<Address>* out) {
  for (uint32_t i = 0; i < n; ++i) {
    Address a;
    if (!bit_address(k, first + i, &a)) return false;
    out->push_back(a);
  }
  return true;
}

uint32_t pack(const std::vector<uint32_t>& v, size_t from, size_t n) {
  uint32_t x = 0;
  for (size_t i = 0; i < n; ++i) x |= (v[from + i] & 1u) << i;
  return x;
}

void string_reads(Address first, uint32_t words, std::vector<Address>* reads) {
  for (uint32_t i = 0; i < words; ++i, ++first.index) reads->push_back(first);
}

std::string unpack_string(const std::vector<uint32_t>& v) {
  std::string s;
  for (uint32_t w : v) {
    for (int sh : {8, 0}) {
      const char c = char((w >> sh) & 0xFF);
      if (c == 0) return s;
      s += c;
    }
  }
  return s;
}

void string_writes(Address first, uint32_t words, const std::string& text,
                   std::vector<std::pair<Address, uint32_t>>* writes) {
  for (uint32_t i = 0; i < words; ++i, ++first.index) {
    const uint32_t hi = 2 * i < text.size() ? uint8_t(text[2 * i]) : 0;
    const uint32_t lo = 2 * i + 1 < text.size() ? uint8_t(text[2 * i + 1]) : 0;
    writes->push_back({first, hi << 8 | lo});
  }
}

// RVS / WVS type and index -> the element(s): a word of discretes or one register.
ErrorCode system_variable(uint32_t type, uint32_t index, std::vector<Address>* elems, bool* bits) {
  *bits = false;
  static const BitKind kWordKinds[] = {BitKind::Input, BitKind::Output, BitKind::Relay, BitKind::Timer,
                                       BitKind::Counter};
  Address a;
  switch (type) {
    case 1: case 2: case 3: case 4: case 5: {
      const BitKind k = kWordKinds[type - 1];
      if (index < 1 || 16 * index > bit_count(k)) return ErrorCode::OutOfRange;
      *bits = true;
      return bits_of(k, 16 * (index - 1) + 1, 16, elems) ? ErrorCode::Ok : ErrorCode::OutOfRange;
    }
    case 6: if (index < 1 || index > kTimers) return ErrorCode::OutOfRange; elems->push_back(timer_pv(index)); break;
    case 7: if (index < 1 || index > kCounters) return ErrorCode::OutOfRange; elems->push_back(counter_pv(index)); break;
    case 8: if (!time_register(index, &a)) return ErrorCode::OutOfRange; elems->push_back(a); break;
    case 9: if (!date_register(index, &a)) return ErrorCode::OutOfRange; elems->push_back(a); break;
    case 0x0B: if (!adc(index, &a)) return ErrorCode::OutOfRange; elems->push_back(a); break;
    case 0x0C: if (!dac(index, &a)) return ErrorCode::OutOfRange; elems->push_back(a); break;
    case 0x0D: if (!pwm(index, &a)) return ErrorCode::OutOfRange; elems->push_back(a); break;
    default: return ErrorCode::OutOfRange;  // 0A: no variable of that type
  }
  return ErrorCode::Ok;
}

void values_as_read(const std::vector<uint32_t>& v, Response* r) { r->values = v; }

uint32_t clamp_decimal(uint32_t v) { return std::min<uint32_t>(v, 9999); }

// A timer or counter register; PV and SV read back clamped to 4 decimal digits.
ErrorCode plan_timer_counter(const Request& req, Plan* p) {
  const uint32_t n = req.a + 1;
  if (n > kTimers) return ErrorCode::OutOfRange;  // as many counters as timers
  const bool timer = req.cmd == Cmd::ReadTimerPv || req.cmd == Cmd::ReadTimerSv ||
                     req.cmd == Cmd::WriteTimerPv || req.cmd == Cmd::WriteTimerSv;
  const bool sv = req.cmd == Cmd::ReadTimerSv || req.cmd == Cmd::ReadCounterSv ||
                  req.cmd == Cmd::WriteTimerSv || req.cmd == Cmd::WriteCounterSv;
  const Address r = timer ? (sv ? timer_sv(n) : timer_pv(n)) : (sv ? counter_sv(n) : counter_pv(n));
  if (req.values.empty()) {
    p->reads.push_back(r);
    p->finish = [](const std::vector<uint32_t>& v, Response* rsp) { rsp->values = {clamp_decimal(v[0])}; };
  } else {
    p->writes.push_back({r, req.values[0]});
  }
  return ErrorCode::Ok;
}

// A system variable: bit groups pack to 16 bits, the date (type 9) converts to and from FBs form.
ErrorCode plan_system(const Request& req, Plan* p) {
  bool bits = false;
  std::vector<Address> elems;
  const ErrorCode e = system_variable(req.a, req.b, &elems, &bits);
  if (e != ErrorCode::Ok) return e;
  const uint32_t type = req.a, index = req.b;
  if (req.cmd == Cmd::ReadSystem) {
    p->reads = elems;
    p->finish = [=](const std::vector<uint32_t>& v, Response* r) {
      uint32_t x = bits ? pack(v, 0, 16) : v[0];
      if (type == 9) x = date_from_fbs(index, uint16_t(x));
      r->values = {x};
    };
  } else if (bits) {
    for (uint32_t i = 0; i < 16; ++i) p->writes.push_back({elems[i], (req.values[0] >> i) & 1u});
  } else {
    const uint32_t v = type == 9 ? date_to_fbs(index, uint16_t(req.values[0])) : req.values[0];
    p->writes.push_back({elems[0], v});
  }
  return ErrorCode::Ok;
}

// B channels from A; a write answers with the count written.
ErrorCode plan_analog(const Request& req, Plan* p) {
  Address a;
  const bool rd = req.cmd == Cmd::ReadAnalog;
  if (req.b < 1) return ErrorCode::BadData;
  for (uint32_t i = 0; i < req.b; ++i) {
    if (rd ? !adc(req.a + i, &a) : !dac(req.a + i, &a)) return ErrorCode::OutOfRange;
    if (rd) p->reads.push_back(a);
    else p->writes.push_back({a, req.values[i]});
  }
  const uint32_t count = req.b;
  p->finish = rd ? values_as_read
                 : std::function<void(const std::vector<uint32_t>&, Response*)>(
                       [count](const std::vector<uint32_t>&, Response* r) { r->values = {count}; });
  return ErrorCode::Ok;
}

// B EEPROM integers from A: a write takes at most 16.
ErrorCode plan_eeprom_ints(const Request& req, Plan* p) {
  Address a;
  const bool rd = req.cmd == Cmd::ReadEepromInts;
  if (req.b < 1 || (!rd && req.b > 16)) return ErrorCode::BadData;
  const uint32_t n = std::min<uint32_t>(req.b, 32);  // more than 32: the first 32
  for (uint32_t i = 0; i < n; ++i) {
    if (!eeprom_int(req.a + i, &a)) return ErrorCode::OutOfRange;
    if (rd) p->reads.push_back(a);
    else p->writes.push_back({a, req.values[i]});
  }
  if (rd) p->finish = values_as_read;
  return ErrorCode::Ok;
}

// Works out the plan of req, or the error it is refused with.
ErrorCode plan(const Request& req, Plan* p) {
  auto single = [&](Address a) { p->reads.push_back(a); };
  BitKind kind;
  Address a;
  switch (req.cmd) {
    case Cmd::ReadInputs: case Cmd::ReadOutputs: case Cmd::ReadRelays: case Cmd::ReadTimerBits:
    case Cmd::ReadCounterBits:
      channel_kind(req.cmd, &kind);
      if (!bits_of(kind, 8 * req.a + 1, 8, &p->reads)) return ErrorCode::OutOfRange;
      p->finish = [](const std::vector<uint32_t>& v, Response* r) { r->values = {pack(v, 0, 8)}; };
      return ErrorCode::Ok;
    case Cmd::WriteInputs: case Cmd::WriteOutputs: case Cmd::WriteRelays: case Cmd::WriteTimerBits:
    case Cmd::WriteCounterBits: {
      channel_kind(req.cmd, &kind);
      std::vector<Address> bits;
      if (!bits_of(kind, 8 * req.a + 1, 8, &bits)) return ErrorCode::OutOfRange;
      for (uint32_t i = 0; i < 8; ++i) p->writes.push_back({bits[i], (req.values[0] >> i) & 1u});
      return ErrorCode::Ok;
    }
    case Cmd::ReadTimerPv: case Cmd::ReadTimerSv: case Cmd::ReadCounterPv: case Cmd::ReadCounterSv:
    case Cmd::WriteTimerPv: case Cmd::WriteTimerSv: case Cmd::WriteCounterPv: case Cmd::WriteCounterSv:
      return plan_timer_counter(req, p);
    case Cmd::ReadInteger:
    case Cmd::WriteInteger:
      if (!integer_var(req.a, &a)) return ErrorCode::OutOfRange;
      if (req.cmd == Cmd::ReadInteger) single(a), p->finish = values_as_read;
      else p->writes.push_back({a, req.values[0]});
      return ErrorCode::Ok;
    case Cmd::ReadString:
    case Cmd::ReadEepromString: {
      const bool var = req.cmd == Cmd::ReadString;
      if (var ? !string_var(req.a, &a) : !eeprom_string(req.a, &a)) return ErrorCode::OutOfRange;
      string_reads(a, var ? kStringWords : kEepromStringChars / 2, &p->reads);
      p->finish = [](const std::vector<uint32_t>& v, Response* r) { r->text = unpack_string(v); };
      return ErrorCode::Ok;
    }
    case Cmd::WriteString:
    case Cmd::WriteEepromString: {
      const bool var = req.cmd == Cmd::WriteString;
      if (var ? !string_var(req.a, &a) : !eeprom_string(req.a, &a)) return ErrorCode::OutOfRange;
      if (req.text.size() > (var ? kStringChars : kEepromStringChars)) return ErrorCode::OutOfRange;
      string_writes(a, var ? kStringWords : kEepromStringChars / 2, req.text, &p->writes);
      return ErrorCode::Ok;
    }
    case Cmd::ReadDm:
    case Cmd::WriteDm:
      if (!dm(req.a, &a)) return ErrorCode::OutOfRange;
      if (req.cmd == Cmd::ReadDm) single(a), p->finish = values_as_read;
      else p->writes.push_back({a, req.values[0]});
      return ErrorCode::Ok;
    case Cmd::ReadSystem:
    case Cmd::WriteSystem:
      return plan_system(req, p);
    case Cmd::ReadHsc:
    case Cmd::WriteHsc:
      if (!hsc_pv(req.a, &a)) return ErrorCode::OutOfRange;
      if (req.cmd == Cmd::ReadHsc) single(a), p->finish = values_as_read;
      else p->writes.push_back({a, req.values[0]});
      return ErrorCode::Ok;
    case Cmd::ReadAnalog:
    case Cmd::WriteAnalog:
      return plan_analog(req, p);
    case Cmd::ReadEepromInts:
    case Cmd::WriteEepromInts:
      return plan_eeprom_ints(req, p);
    case Cmd::ForceBit: {
      static const BitKind kKinds[] = {BitKind::Input, BitKind::Output, BitKind::Timer, BitKind::Counter,
                                       BitKind::Relay, BitKind::Relay};
      const uint32_t group = req.a >> 8, n = (req.a & 0xFF) + 1 + (group == 5 ? 256 : 0);
      if (group > 5 || !bit_address(kKinds[group], n, &a)) return ErrorCode::OutOfRange;
      p->writes.push_back({a, req.values[0]});
      return ErrorCode::Ok;
    }
    default: return ErrorCode::Ok;  // ID, halt, resume: no memory
  }
}

uint32_t elements_written(const Address& a) {
  return a.width == Width::DWord && a.area != Area::RC ? 2 : 1;
}

}  // namespace

Slave::Slave(Plc& plc, int id) : plc_(plc), id_(id) {
  if (id < 0 || id > 255) throw Error("TRi device ID " + std::to_string(id) + " outside 0..255 (00-FF)");
}

Response Slave::execute(const Request& req) {
  Response rsp;
  rsp.cmd = req.cmd;
  rsp.header = req.header;
  switch (req.cmd) {
    case Cmd::ReadId:
      rsp.values = {uint32_t(id_)};
      return rsp;
    case Cmd::WriteId:
      if (!writable_.everything()) rsp.error = ErrorCode::NotWritable;
      else id_ = int(req.a);
      return rsp;
    case Cmd::Halt:
      if (!writable_.everything()) rsp.error = ErrorCode::NotWritable;
      else if (plc_.mode() == RunMode::Run) {
        plc_.set_mode(RunMode::Stop);
        halted_ = true;
      }
      return rsp;
    case Cmd::Resume:
      if (!writable_.everything()) rsp.error = ErrorCode::NotWritable;
      else if (halted_.exchange(false) && !plc_.set_mode(RunMode::Run)) rsp.error = ErrorCode::CannotExecute;
      return rsp;
    default: break;
  }
  Plan p;
  rsp.error = plan(req, &p);
  if (rsp.error != ErrorCode::Ok) return rsp;
  for (const auto& w : p.writes)
    if (!writable_.allows(w.first.area, w.first.index, elements_written(w.first))) {
      rsp.error = ErrorCode::NotWritable;
      return rsp;
    }
  std::vector<uint32_t> got;
  got.reserve(p.reads.size());
  plc_.locked([&](ScanEngine& e, Memory& m) {
    for (const auto& a : p.reads) got.push_back(m.read(a));
    for (const auto& w : p.writes) {
      m.write(w.first, w.second);
      // Writing an input plays the sensor: the terminal keeps the level (as Plc::write).
      if (w.first.area == Area::X && !m.disabled(Area::X, w.first.index)) e.set_input(w.first.index, w.second & 1u);
    }
    return 0;
  });
  if (!p.writes.empty()) plc_.commit();  // durable before it is acknowledged
  if (p.finish) p.finish(got, &rsp);
  return rsp;
}

bool Slave::handle(const Decoder::Event& ev, std::string& out) {
  switch (ev.kind) {
    case Decoder::Event::Enquiry:
      out += kEnq;
      return true;
    case Decoder::Event::Error:
      ++rejected_;
      return false;
    case Decoder::Event::FrameReady: break;
  }
  const Frame& f = ev.frame;
  const int my_id = id_;
  if (f.multipoint && f.id != my_id) return false;  // another PLC's: stay silent
  Frame reply;
  reply.multipoint = f.multipoint;
  reply.id = my_id;
  if (f.multipoint && !ev.fcs_ok) {
    ++rejected_;
    reply.body = "FE";  // plc_cell's framing-error response
    out += encode_frame(reply);
    return true;
  }
  Request req;
  Response rsp;
  rsp.error = parse_request(f.body, &req);
  if (rsp.error == ErrorCode::Ok) rsp = execute(req);
  if (rsp.error == ErrorCode::Ok) ++requests_;
  else ++rejected_;
  reply.body = encode_response(req, rsp);
  out += encode_frame(reply);
  return true;
}

std::string Slave::answer(std::string_view bytes, bool wildcard) {
  Decoder dec(wildcard);
  std::string out;
  dec.feed(bytes, [&](const Decoder::Event& ev) { handle(ev, out); });
  return out;
}

}  // namespace tri
}  // namespace plc_cell
