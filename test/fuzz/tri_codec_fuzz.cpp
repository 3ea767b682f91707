// Any bytes as a TRi request body and as the response a master receives: parsing never
// crashes, and what parses is stable under re-encoding. A master (tri_bridge) must survive
// whatever a device or a man in the middle sends back.
//   input = request body '\n' response body
// Invariants (abort = finding):
//   * a parsed request re-encodes to a body that parses to the same encoding;
//   * a response that parses without error re-encodes to a body that parses to the same
//     values and text.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "plc_cell/tri/commands.h"

using namespace plc_cell::tri;

namespace {

[[noreturn]] void finding(const char* what, std::string_view a, std::string_view b) {
  std::fprintf(stderr, "tri codec: %s: '%.*s' / '%.*s'\n", what, int(a.size()), a.data(), int(b.size()), b.data());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view in(reinterpret_cast<const char*>(data), size);
  const size_t nl = in.find('\n');
  const std::string_view req_body = in.substr(0, nl);
  const std::string_view rsp_body = nl == std::string_view::npos ? std::string_view() : in.substr(nl + 1);

  Request req;
  if (parse_request(req_body, &req) != ErrorCode::Ok) return 0;
  const std::string once = encode_request(req);
  Request again;
  if (parse_request(once, &again) != ErrorCode::Ok) finding("re-encoded request refused", req_body, once);
  if (encode_request(again) != once) finding("request encoding not stable", req_body, once);

  Response rsp;
  if (!parse_response(req, rsp_body, &rsp)) return 0;
  if (rsp.error != ErrorCode::Ok) return 0;
  const std::string body = encode_response(req, rsp);
  Response back;
  if (!parse_response(req, body, &back)) finding("re-encoded response refused", rsp_body, body);
  if (back.values != rsp.values || back.text != rsp.text) finding("response values changed", rsp_body, body);
  return 0;
}
