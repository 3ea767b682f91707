#include "plc_cell/fatek/slave.h"

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"

namespace plc_cell {
namespace fatek {
namespace {

bool is_write(Cmd c) {
  return c == Cmd::RunStop || c == Cmd::Control || c == Cmd::WriteDiscretes || c == Cmd::WriteRegisters ||
         c == Cmd::MixedWrite;
}

// As Plc::write: writing an input X plays the sensor, so the terminal keeps the level.
void write_point(ScanEngine& e, Memory& m, const Address& a, uint32_t v) {
  m.write(a, v);
  if (a.area != Area::X) return;
  const int n = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  for (int k = 0; k < n; ++k)
    if (!m.disabled(Area::X, a.index + k)) e.set_input(a.index + k, (v >> k) & 1u);
}

// The elements a request writes: WY8 is Y8..Y23, DR0 is R0 and R1.
bool may_write(const WritableRanges& w, const Address& a, uint32_t count) {
  uint32_t per = 1;
  if (is_discrete(a.area)) per = a.width == Width::Word ? 16 : a.width == Width::DWord ? 32 : 1;
  else if (a.width == Width::DWord && a.area != Area::RC) per = 2;
  return w.allows(a.area, a.index, count * per);
}

ErrorCode check_writable(const WritableRanges& w, const Request& req) {
  if (w.everything()) return ErrorCode::Ok;
  switch (req.cmd) {
    case Cmd::RunStop: return ErrorCode::Format;  // "command cannot execute"
    case Cmd::Control: return may_write(w, req.start, 1) ? ErrorCode::Ok : ErrorCode::IllegalAddress;
    case Cmd::WriteDiscretes:
    case Cmd::WriteRegisters: return may_write(w, req.start, req.count) ? ErrorCode::Ok : ErrorCode::IllegalAddress;
    case Cmd::MixedWrite:
      for (const auto& p : req.points)
        if (!may_write(w, p, 1)) return ErrorCode::IllegalAddress;
      return ErrorCode::Ok;
    default: return ErrorCode::Ok;
  }
}

uint8_t status1(ScanEngine& e) {
  uint8_t s = 0;
  if (e.mode() == RunMode::Run) s |= kStatusRun;
  if (!e.interpreter().loaded()) s |= kStatusLadderChecksum;
  if (e.watchdog_tripped()) s |= kStatusWatchdog;
  return s;
}

void put16(std::vector<uint8_t>& v, uint32_t x) {
  v.push_back(uint8_t(x >> 8));
  v.push_back(uint8_t(x));
}

}  // namespace

Slave::Slave(Plc& plc, int station) : plc_(plc), station_(station) {
  if (station < 1 || station > 254) throw Error("FATEK station " + std::to_string(station) + " outside 1..254");
}

bool Slave::handle(const Frame& f, std::string& out) {
  const bool broadcast = f.station == 0;
  if (!broadcast && f.station != station_) return false;  // multi-drop: not for us, stay silent
  Request req;
  Response rsp;
  rsp.station = uint8_t(station_);
  ErrorCode e = parse_request(f, &req);
  if (e == ErrorCode::Ok) e = check_writable(writable_, req);
  if (broadcast) {
    // Broadcast: execute write-type commands, never answer (spec 1.6).
    if (e == ErrorCode::Ok && is_write(req.cmd)) e = execute(req, &rsp);
    if (e == ErrorCode::Ok) ++requests_;
    else ++rejected_;
    return false;
  }
  if (e == ErrorCode::Ok) e = execute(req, &rsp);
  rsp.error = e;
  if (e == ErrorCode::Ok) ++requests_;
  else ++rejected_;
  if (e != ErrorCode::Ok) {
    rsp.values.clear();
    rsp.status.clear();
  }
  append_response(out, req, rsp);
  return true;
}

ErrorCode Slave::execute(const Request& req, Response* rsp) {
  switch (req.cmd) {
    case Cmd::RunStop:
      // No program to run is reported as the ladder checksum error (code 5).
      return plc_.set_mode(req.run ? RunMode::Run : RunMode::Stop) ? ErrorCode::Ok : ErrorCode::LadderChecksum;
    case Cmd::Control: {
      static const ForceAction kActions[] = {ForceAction::Disable, ForceAction::Enable, ForceAction::Set,
                                             ForceAction::Reset};
      plc_.force(req.start, kActions[uint8_t(req.action) - 1]);
      return ErrorCode::Ok;
    }
    case Cmd::Loopback:
      rsp->text = req.text;
      return ErrorCode::Ok;
    default: break;
  }
  // Everything else runs whole inside one lock, so it is atomic with respect to the scan.
  plc_.locked([&](ScanEngine& e, Memory& m) {
    switch (req.cmd) {
      case Cmd::GistStatus:
        rsp->status = {status1(e), 0, 0};
        break;
      case Cmd::DetailedStatus: {
        auto& s = rsp->status;
        s = {status1(e), 0x01, 0x02, 0x40};  // unit type, I/O points code, OS 4.0x (spec 1.9 example)
        put16(s, 0x8000);                        // ladder capacity, words
        put16(s, area_size(Area::X));
        put16(s, area_size(Area::Y));
        put16(s, 0x0064);                        // analog inputs / outputs (R3840.. ranges)
        put16(s, 0x0064);
        put16(s, area_size(Area::M));
        put16(s, area_size(Area::S));
        put16(s, 0);                             // L relays: none on the FBs
        put16(s, area_size(Area::R));
        put16(s, area_size(Area::D));
        put16(s, area_size(Area::RT));
        put16(s, area_size(Area::RC));
        break;
      }
      case Cmd::ReadEnable:
        for (uint32_t i = 0; i < req.count; ++i)
          rsp->values.push_back(m.disabled(req.start.area, req.start.index + i) ? 1 : 0);  // '1' = DISABLE
        break;
      case Cmd::ReadDiscretes:
      case Cmd::ReadRegisters: {
        // The whole range was checked above; step through it without re-checking each element.
        Address a = req.start;
        const uint32_t stride = element_stride(a);
        rsp->values.reserve(req.count);
        for (uint32_t i = 0; i < req.count; ++i, a.index += stride) rsp->values.push_back(m.read(a));
        break;
      }
      case Cmd::WriteDiscretes:
      case Cmd::WriteRegisters:
      {
        Address a = req.start;
        const uint32_t stride = element_stride(a);
        for (uint32_t i = 0; i < req.count; ++i, a.index += stride) write_point(e, m, a, req.values[i]);
        break;
      }
      case Cmd::MixedRead:
        for (const auto& p : req.points) rsp->values.push_back(m.read(p));
        break;
      case Cmd::MixedWrite:
        for (size_t i = 0; i < req.points.size(); ++i) write_point(e, m, req.points[i], req.values[i]);
        break;
      default: break;
    }
    return 0;
  });
  // The reply is built after this returns: a write is durable before it is acknowledged.
  if (req.cmd == Cmd::WriteDiscretes || req.cmd == Cmd::WriteRegisters || req.cmd == Cmd::MixedWrite) plc_.commit();
  return ErrorCode::Ok;
}

}  // namespace fatek
}  // namespace plc_cell
