#pragma once
// What the TCP server hands requests for other unit ids to (the gateway's RTU side).
#include <cstdint>
#include <functional>
#include <vector>

namespace plc_cell {
namespace modbus {

class Forwarder {
 public:
  // reply: a complete Modbus/TCP ADU for the request's connection.
  using Done = std::function<void(uint64_t conn, std::vector<uint8_t> reply)>;
  virtual ~Forwarder() = default;
  // frame: the whole Modbus/TCP ADU (MBAP + PDU). done is called exactly once,
  // from another thread, unless submit returns false (then nothing is queued).
  virtual bool submit(uint64_t conn, std::vector<uint8_t> frame, Done done) = 0;
};

// A Modbus/TCP exception reply to frame (same transaction id and unit).
std::vector<uint8_t> tcp_exception(const std::vector<uint8_t>& frame, uint8_t code);

}  // namespace modbus
}  // namespace plc_cell
