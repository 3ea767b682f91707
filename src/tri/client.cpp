#include "plc_cell/tri/client.h"

#include <chrono>
#include <cstdio>

#include "plc_cell/tri/frame.h"

namespace plc_cell {
namespace tri {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

Client::Client(std::unique_ptr<Transport> t, ClientOptions opt) : t_(std::move(t)), opt_(opt) {
  if (opt_.id < 0 || opt_.id > 255) throw Error("TRi device ID " + std::to_string(opt_.id) + " outside 0..255");
}

Response Client::once(const Request& req, const std::string& body, const std::string& bytes) {
  char buf[512];
  // The reply's FCS is checked as sent: "00" is only the wildcard in a request.
  Decoder dec(false);
  const auto t0 = Clock::now();
  ++requests_;
  t_->send(bytes, opt_.timeout_ms);
  const auto deadline = t0 + std::chrono::milliseconds(opt_.timeout_ms);
  bool done = false;
  Response rsp;
  std::string why;
  while (!done) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
    if (left <= 0) break;
    const size_t n = t_->recv(buf, sizeof buf, int(left));
    dec.feed(reinterpret_cast<const uint8_t*>(buf), n, [&](const Decoder::Event& ev) {
      if (done || ev.kind != Decoder::Event::FrameReady) return;
      if (!ev.frame.multipoint || ev.frame.id != opt_.id) return;  // not an answer to us
      done = true;
      if (!ev.fcs_ok) why = "reply to " + body + " with a bad FCS";
      else if (ev.frame.body == "FE") why = "the PLC reports a framing error (FCS) in " + body;
      else if (!parse_response(req, ev.frame.body, &rsp)) why = "bad answer to " + body + ": '" + ev.frame.body + "'";
    });
  }
  if (!done)
    throw CommError(t_->describe() + ": no answer to " + body + " within " + std::to_string(opt_.timeout_ms) + " ms");
  if (!why.empty()) throw CommError(t_->describe() + ": " + why);
  last_latency_us_ = uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - t0).count());
  return rsp;
}

Response Client::transact(const Request& req) {
  Frame f;
  f.multipoint = true;
  f.id = opt_.id;
  f.body = encode_request(req);
  const std::string bytes = encode_frame(f);
  return with_retries(*t_, opt_.retries, opt_.timeout_ms, &retries_used_, [&] {
    Response rsp = once(req, f.body, bytes);
    if (rsp.error != ErrorCode::Ok) {
      char code[8];
      std::snprintf(code, sizeof code, "ER%02X", unsigned(rsp.error));
      throw PlcError(rsp.error, "TRi error " + std::string(code) + " (" + error_name(rsp.error) + ") to " + f.body);
    }
    return rsp;
  });
}

}  // namespace tri
}  // namespace plc_cell
