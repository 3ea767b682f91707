#include "plc_cell/fatek/client.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace plc_cell {
namespace fatek {
namespace {

using Clock = std::chrono::steady_clock;

std::string cmd_hex(Cmd c) {
  char b[4];
  std::snprintf(b, sizeof b, "%02X", unsigned(c));
  return b;
}

}  // namespace

uint32_t max_block(const Address& start) {
  if (start.width == Width::Bit) return kMaxDiscretes;
  return start.width == Width::Word ? kMaxWords : kMaxDWords;
}

Client::Client(std::unique_ptr<Transport> t, ClientOptions opt) : t_(std::move(t)), opt_(opt) {}

Response Client::once(const Request& req, const std::string& bytes) {
  char buf[512];
  dec_.reset();
  const auto t0 = Clock::now();
  t_->send(bytes, opt_.timeout_ms);
  if (req.station == 0) return Response{};  // broadcast: nobody answers
  const auto deadline = t0 + std::chrono::milliseconds(opt_.timeout_ms);
  for (;;) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) break;
    const size_t n = t_->recv(buf, sizeof buf, int(left));
    for (size_t i = 0; i < n; ++i) {
      if (dec_.push(uint8_t(buf[i])) != Decoder::Status::Frame) continue;
      Response rsp;
      std::string why;
      if (dec_.frame().station != req.station && req.station != 0) continue;  // another slave's
      if (!parse_response(req, dec_.frame(), &rsp, &why)) throw CommError("bad answer to command " + cmd_hex(req.cmd) + ": " + why);
      last_latency_us_ = uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count());
      return rsp;
    }
  }
  throw CommError(t_->describe() + ": no answer to command " + cmd_hex(req.cmd) + " within " +
                  std::to_string(opt_.timeout_ms) + " ms");
}

Response Client::transact(Request req) {
  req.station = uint8_t(opt_.station);
  if (req.station == 0 && req.cmd != Cmd::RunStop && req.cmd != Cmd::Control && req.cmd != Cmd::WriteDiscretes &&
      req.cmd != Cmd::WriteRegisters && req.cmd != Cmd::MixedWrite)
    throw Error("station 0 is broadcast: nobody answers command " + cmd_hex(req.cmd) + "; only writes can be broadcast");
  const std::string bytes = encode_request(req);
  return with_retries(*t_, opt_.retries, opt_.timeout_ms, &retries_used_, [&] {
    Response rsp = once(req, bytes);
    if (rsp.error != ErrorCode::Ok)
      throw PlcError(rsp.error, "PLC error " + std::string(1, char(rsp.error)) + " (" + error_text(rsp.error) +
                                    ") to command " + cmd_hex(req.cmd));
    return rsp;
  });
}

static PlcStatus to_status(const Response& r) {
  PlcStatus s;
  s.bytes = r.status;
  s.status1 = r.status.empty() ? 0 : r.status[0];
  s.run = s.status1 & 1;
  return s;
}

PlcStatus Client::status() {
  Request r;
  r.cmd = Cmd::GistStatus;
  return to_status(transact(r));
}

PlcStatus Client::detailed_status() {
  Request r;
  r.cmd = Cmd::DetailedStatus;
  return to_status(transact(r));
}

void Client::set_run(bool run) {
  Request r;
  r.cmd = Cmd::RunStop;
  r.run = run;
  transact(r);
}

void Client::control(const Address& point, Action a) {
  Request r;
  r.cmd = Cmd::Control;
  r.start = point;
  r.action = a;
  transact(r);
}

std::vector<bool> Client::read_disabled(const Address& start, uint32_t count) {
  if (start.width != Width::Bit) throw Error("read_disabled needs a discrete address");
  check_span(start, count);
  std::vector<bool> out;
  for (uint32_t done = 0; done < count;) {
    Request r;
    r.cmd = Cmd::ReadEnable;
    r.start = offset_address(start, done);
    r.count = std::min(count - done, kMaxDiscretes);
    for (uint32_t v : transact(r).values) out.push_back(v != 0);
    done += r.count;
  }
  return out;
}

std::vector<uint32_t> Client::read(const Address& start, uint32_t count) {
  check_span(start, count);
  std::vector<uint32_t> out;
  out.reserve(count);
  for (uint32_t done = 0; done < count;) {
    Request r;
    r.cmd = start.width == Width::Bit ? Cmd::ReadDiscretes : Cmd::ReadRegisters;
    r.start = offset_address(start, done);
    r.count = std::min(count - done, max_block(start));
    const Response rsp = transact(r);
    out.insert(out.end(), rsp.values.begin(), rsp.values.end());
    done += r.count;
  }
  return out;
}

void Client::write(const Address& start, const std::vector<uint32_t>& values) {
  const uint32_t count = uint32_t(values.size());
  check_span(start, count);
  for (uint32_t done = 0; done < count;) {
    Request r;
    r.cmd = start.width == Width::Bit ? Cmd::WriteDiscretes : Cmd::WriteRegisters;
    r.start = offset_address(start, done);
    r.count = std::min(count - done, max_block(start));
    r.values.assign(values.begin() + done, values.begin() + done + r.count);
    transact(r);
    done += r.count;
  }
}

std::vector<uint32_t> Client::read_mixed(const std::vector<Address>& points) {
  std::vector<uint32_t> out;
  size_t i = 0;
  while (i < points.size()) {
    Request r;
    r.cmd = Cmd::MixedRead;
    uint32_t w = 0;
    while (i < points.size() && w + weight(points[i]) <= kMaxMixedReadWeight) {
      w += weight(points[i]);
      r.points.push_back(points[i++]);
    }
    const Response rsp = transact(r);
    out.insert(out.end(), rsp.values.begin(), rsp.values.end());
  }
  return out;
}

void Client::write_mixed(const std::vector<Address>& points, const std::vector<uint32_t>& values) {
  if (points.size() != values.size()) throw Error("write_mixed: points and values differ in number");
  size_t i = 0;
  while (i < points.size()) {
    Request r;
    r.cmd = Cmd::MixedWrite;
    uint32_t w = 0;
    while (i < points.size() && w + weight(points[i]) <= kMaxMixedWriteWeight) {
      w += weight(points[i]);
      r.values.push_back(values[i]);
      r.points.push_back(points[i++]);
    }
    transact(r);
  }
}

std::string Client::loopback(const std::string& text) {
  Request r;
  r.cmd = Cmd::Loopback;
  r.text = text;
  return transact(r).text;
}

}  // namespace fatek
}  // namespace plc_cell
