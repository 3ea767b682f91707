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

#include "edit_desk.h"
#include "ladder_view.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/source_set.h"
#include "request_guard.h"

namespace plc_cell {
namespace monitor {

constexpr size_t kMaxBody = 64 * 1024;
// A program's text (POST /api/edit/...) may be longer than any other request.
constexpr size_t kMaxProgramBody = 1024 * 1024;
inline size_t max_body(const std::string& target) {
  return target.rfind("/api/edit/", 0) == 0 ? kMaxProgramBody : kMaxBody;
}
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
  nlohmann::json status_now() { return status_json_now(); }  // GET /api/status's, gathered now
  // A page's read of the source went ("" ) or failed (why): a change is logged once.
  void note_read(const std::string& failure);
  Source& source() { return source_; }
  // The cells this Api's cell is served with (a line's): their qualified names (robot.X3)
  // are read from them. nullptr or a set of one: the cell alone.
  void serve_in(const SourceSet* set, size_t self) {
    set_ = set;
    self_ = self;
  }
  const SourceSet* set() const { return set_; }
  size_t self() const { return self_; }
  const std::string& token() const { return token_; }

 private:
  nlohmann::json status_json_now();
  ApiReply get(const std::string& path, const std::string& query);
  ApiReply post(const std::string& path, const nlohmann::json& body);
  ApiReply read(const std::string& query);
  ApiReply access(const std::string& query);
  ApiReply write(const nlohmann::json& body);
  ApiReply force(const nlohmann::json& body);
  ApiReply mode(const nlohmann::json& body);
  ApiReply replay_get();
  ApiReply replay_history(const std::string& query);
  ApiReply replay_post(const nlohmann::json& body);
  ApiReply refuse_write(const std::string& what, const std::string& why);
  // A name qualified by another cell of the set: true with where it is.
  bool foreign(const std::string& name, Located* at) const;
  ApiReply edit_get(const std::string& path, const std::string& query);
  ApiReply edit_post(const std::string& path, const nlohmann::json& body);
  // "" when the elements from a may be written, else why not.
  std::string not_writable(const Address& a, uint32_t elements) const;
  // Why a page may not make this change at all here ("" = it may, within the ranges).
  std::string cannot(Change c) const;
  std::string cannot_write(const Address& a, uint32_t count) const;
  std::string cannot_force(const Address& a) const;
  std::string cannot_switch_mode() const;
  // A change the page asked for: refused (refusal not empty, or change throws) or done;
  // logged to every page either way.
  ApiReply apply(const std::string& what, const std::string& refusal, const std::function<void()>& change);
  void log(const std::string& text);

  Source& source_;
  const SourceSet* set_ = nullptr;
  size_t self_ = 0;
  const HttpSettings& settings_;
  RequestGuard guard_;
  std::string token_;
  Events events_;
  std::mutex ladder_mu_;
  std::shared_ptr<const LadderView> ladder_;
  std::mutex status_mu_;
  nlohmann::json status_;  // the last status message, and when it was gathered
  std::chrono::steady_clock::time_point status_at_;
  std::mutex read_mu_;
  enum class ReadState { Unknown, Up, Down } read_state_ = ReadState::Unknown;
  std::chrono::steady_clock::time_point down_since_;
  std::unique_ptr<EditDesk> edit_;  // last: its job thread may log through this Api
};

// The elements of the memory a write of count values at a covers: WY8 x1 is Y8..Y23,
// DR0 x1 is R0 and R1.
uint32_t elements(const Address& a, uint32_t count);

}  // namespace monitor
}  // namespace plc_cell
