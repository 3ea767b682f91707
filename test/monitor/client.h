#pragma once
// A minimal HTTP and WebSocket client for the monitor's tests (Boost.Beast in client.cpp
// only). Every call is bounded in time: a server that does not answer fails the test.
#include <chrono>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace plc_cell {
namespace monitor_test {

struct HttpCall {
  std::string method = "GET";
  std::string target = "/";
  std::string host;  // "" = 127.0.0.1:<port>
  std::string origin;
  std::string token;
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;
};

struct HttpReply {
  int status = 0;  // 0: no answer (connection closed or timed out)
  std::string body;
  std::string content_type;
  nlohmann::json json() const { return nlohmann::json::parse(body, nullptr, false); }
};

HttpReply http_call(uint16_t port, const HttpCall& call);
inline HttpReply http_get(uint16_t port, const std::string& target) {
  HttpCall c;
  c.target = target;
  return http_call(port, c);
}
HttpReply http_post(uint16_t port, const std::string& target, const std::string& body, const std::string& token);

// Sends bytes as they are and returns what came back until the server closed or timeout.
std::string raw_exchange(uint16_t port, const std::string& bytes,
                         std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
// True when the server closes a connection that sends bytes (and then nothing) within timeout.
bool closed_after_sending(uint16_t port, const std::string& bytes, std::chrono::milliseconds timeout);
inline bool closed_when_silent(uint16_t port, std::chrono::milliseconds timeout) {
  return closed_after_sending(port, "", timeout);
}

// n connections that each send bytes (half a request, say) and then wait, reading nothing:
// they stay open until the server closes them or this object goes.
class Stallers {
 public:
  Stallers(uint16_t port, size_t n, const std::string& bytes);
  ~Stallers();
  size_t open();  // how many the server has not closed yet (looked at without waiting)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class WsClient {
 public:
  // Throws when the upgrade is refused; *status (if given) gets the refusal's status.
  WsClient(uint16_t port, const std::string& host = "", const std::string& origin = "",
           const std::string& target = "/api/live");
  ~WsClient();
  void send(const std::string& text);
  // The next message whose "type" is type (others are skipped); null when none came
  // within timeout or the connection closed.
  nlohmann::json next(const std::string& type, std::chrono::milliseconds timeout = std::chrono::milliseconds(3000));
  // The next message of any type ("" type: next(type) with this skips none).
  nlohmann::json next_any(std::chrono::milliseconds timeout = std::chrono::milliseconds(3000)) {
    return next("", timeout);
  }
  // True when the server closed the connection within timeout.
  bool closed_within(std::chrono::milliseconds timeout);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The status answering a WebSocket upgrade: 101 when accepted.
int ws_upgrade(uint16_t port, const std::string& host, const std::string& origin, const std::string& target = "/api/live");

}  // namespace monitor_test
}  // namespace plc_cell
