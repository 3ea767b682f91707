#pragma once
// The monitor's HTTP API on a Source, without the transport (docs/monitor-api.md): the
// Beast sessions hand each request here as plain text and send back what it returns, so
// every rule (guard, token, writable ranges, limits, errors) is in this one place.
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>

#include <nlohmann/json.hpp>

#include "ladder_view.h"
#include "plc_cell/monitor/http_server.h"
#include "request_guard.h"

namespace plc_cell {
namespace monitor {

constexpr size_t kMaxBody = 64 * 1024;
constexpr size_t kMaxWriteValues = 256;

struct ApiRequest {
  std::string method;  // "GET", "POST", ...
  std::string target;  // path and query
  std::string host, origin, token;
  std::string body;
};

struct ApiReply {
  int status = 200;
  std::string type = "application/json";
  std::string body;
};

class Api {
 public:
  struct Events {
    std::function<void(const std::string&)> log;  // a {"type":"log"} message for every page
    std::function<void()> moved;                  // the replay cursor moved: frames now
  };
  Api(Source& source, const HttpSettings& settings, const std::string& bound_host, std::string token, Events events);

  // Host and Origin: "" when the request may go on.
  std::string refusal(const ApiRequest& r) const { return guard_.refusal(r.host, r.origin); }
  // Every request but the WebSocket upgrade; never throws.
  ApiReply handle(const ApiRequest& r);
  // The layout of the source's current program (rebuilt when its version changes).
  std::shared_ptr<const LadderView> ladder();
  nlohmann::json status_message();  // {"type":"status", ...}
  Source& source() { return source_; }
  const std::string& token() const { return token_; }

 private:
  nlohmann::json status_json_now();
  ApiReply get(const std::string& path, const std::string& query);
  ApiReply post(const std::string& path, const nlohmann::json& body);
  ApiReply read(const std::string& query);
  ApiReply write(const nlohmann::json& body);
  ApiReply force(const nlohmann::json& body);
  ApiReply mode(const nlohmann::json& body);
  ApiReply replay_get();
  ApiReply replay_history(const std::string& query);
  ApiReply replay_post(const nlohmann::json& body);
  ApiReply refuse_write(const std::string& what, const std::string& why);
  // "" when the elements from a may be written, else why not.
  std::string not_writable(const Address& a, uint32_t elements) const;
  // A change the page asked for: refused (refusal not empty, or change throws) or done;
  // logged to every page either way.
  ApiReply apply(const std::string& what, const std::string& refusal, const std::function<void()>& change);
  void log(const std::string& text);

  Source& source_;
  const HttpSettings& settings_;
  RequestGuard guard_;
  std::string token_;
  Events events_;
  std::mutex ladder_mu_;
  std::shared_ptr<const LadderView> ladder_;
  std::mutex status_mu_;
  nlohmann::json status_;  // the last status message, and when it was gathered
  std::chrono::steady_clock::time_point status_at_;
};

}  // namespace monitor
}  // namespace plc_cell
