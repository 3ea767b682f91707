#include <algorithm>

#include "json_views.h"
#include "sessions.h"

namespace plc_cell {
namespace monitor {

void Hub::broadcast(const Api* cell, const std::string& message) {
  for (auto it = pages.begin(); it != pages.end();) {
    if (auto p = it->lock()) {
      if (p->api() == cell) p->send(message);
      ++it;
    } else {
      it = pages.erase(it);
    }
  }
}

void Hub::frames_now() {
  for (auto& w : pages)
    if (auto p = w.lock()) p->send_frame();
}

// The Host and Origin rules first, for every request: a refused page learns nothing more.
ApiReply Hub::answer(const Route& to, const ApiRequest& r) {
  if (to.api) return to.api->handle(r);
  if (const std::string why = apis.front()->refusal(r); !why.empty()) return {403, "application/json", error_body(why)};
  if (!to.error.empty()) return {404, "application/json", error_body(to.error)};
  const std::string path = r.target.substr(0, r.target.find('?'));
  if (r.method != "GET") return {405, "application/json", error_body(r.method + " " + path + ": the overview answers GET only")};
  return overview->get(path);
}

Hub::Hub(const HttpSettings& s)
    : settings(s),
      table(ConnectionLimits{s.max_connections, int(s.idle_timeout_us / 1000),
                             int(s.header_timeout_us / 1000), /*evict_after_ms=*/0}) {}

Connections<std::weak_ptr<Closable>>::Conn* Hub::conn(uint64_t id) {
  for (auto& c : table.all())
    if (c.id == id) return &c;
  return nullptr;
}

Slot::~Slot() {
  auto& all = hub_.table.all();
  all.erase(std::remove_if(all.begin(), all.end(), [this](const auto& c) { return c.id == id_; }), all.end());
  --hub_.connections;
}

void Slot::owner(std::weak_ptr<Closable> c) {
  if (auto* e = hub_.conn(id_)) e->x = std::move(c);
}

void Slot::partial() {
  if (auto* e = hub_.conn(id_)) Connections<std::weak_ptr<Closable>>::partial(*e, std::chrono::steady_clock::now());
}

void Slot::complete() {
  if (auto* e = hub_.conn(id_)) Connections<std::weak_ptr<Closable>>::complete(*e, std::chrono::steady_clock::now());
}

void Slot::waiting(bool w) {
  if (auto* e = hub_.conn(id_)) e->waiting = w;
}

HttpSession::HttpSession(tcp::socket socket, Hub& hub, std::unique_ptr<Slot> slot)
    : stream_(std::move(socket)), hub_(hub), slot_(std::move(slot)) {}

void HttpSession::run() {
  if (!slot_) {
    ++hub_.rejected;
    reply(503, "application/json",
          error_body("too many connections (max_connections " + std::to_string(hub_.settings.max_connections) +
                     ", every one busy)"),
          false);
    return;
  }
  slot_->owner(weak_from_this());
  read();
}

void HttpSession::evict() {
  beast::error_code ignored;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
  stream_.socket().close(ignored);
}

// A request in three steps, so that the table knows where it is: its first byte (awaited
// for the idle timeout), its headers (whole within header_timeout of the first byte), its
// body (at most kMaxBody).
void HttpSession::read() {
  parser_ = std::make_unique<http::request_parser<http::string_body>>();
  parser_->header_limit(16 * 1024);
  parser_->body_limit(kMaxBody);
  if (buffer_.size()) return on_first_bytes();  // the next request came with the last
  stream_.expires_after(hub_.idle());
  stream_.async_read_some(buffer_.prepare(4096), [self = shared_from_this()](beast::error_code ec, size_t n) {
    if (ec) return self->end(ec);
    self->buffer_.commit(n);
    self->on_first_bytes();
  });
}

void HttpSession::on_first_bytes() {
  slot_->partial();
  stream_.expires_after(hub_.header_time());
  http::async_read_header(stream_, buffer_, *parser_, [self = shared_from_this()](beast::error_code ec, size_t) {
    self->on_header(ec);
  });
}

void HttpSession::on_header(beast::error_code ec) {
  if (ec) return on_read(ec, 0);
  if (parser_->is_done()) return on_read({}, 0);
  parser_->body_limit(max_body(std::string(parser_->get().target())));
  stream_.expires_after(hub_.idle());
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
}

void HttpSession::end(beast::error_code) {
  beast::error_code ignored;
  stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
}

namespace {

// A refused request's status: what the parser could not take.
int parse_error_status(const beast::error_code& ec) {
  if (ec == http::error::body_limit) return 413;
  if (ec == http::error::header_limit) return 431;
  return 400;
}

std::string header(const http::request<http::string_body>& r, http::field f) {
  auto it = r.find(f);
  return it == r.end() ? "" : std::string(it->value());
}

}  // namespace

void HttpSession::on_read(beast::error_code ec, size_t) {
  if (ec == http::error::end_of_stream || ec == beast::error::timeout || ec == net::error::eof ||
      ec == net::error::connection_reset || ec == net::error::operation_aborted || ec == net::error::bad_descriptor)
    return end(ec);
  slot_->complete();
  slot_->waiting(true);  // answering: not a stale connection
  if (ec) {
    ++hub_.rejected;
    const std::string limit = std::to_string(max_body(std::string(parser_->get().target())));
    const std::string why = ec == http::error::body_limit ? "request body over the limit of " + limit + " bytes"
                            : ec == http::error::header_limit ? "request header over the limit of 16384 bytes"
                                                                : "malformed HTTP request: " + ec.message();
    reply(parse_error_status(ec), "application/json", error_body(why), false);
    return;
  }
  auto req = parser_->release();
  const Route to = route(std::string(req.target()), *hub_.set, hub_.apis);
  if (websocket::is_upgrade(req)) {
    const std::string why =
        hub_.apis.front()->refusal({"GET", "", header(req, http::field::host), header(req, http::field::origin), "", ""});
    const bool live = to.api && to.target == "/api/live";
    if (!why.empty() || !live) {
      ++hub_.rejected;
      const std::string where = !to.error.empty() ? to.error : std::string(req.target()) + ": the WebSocket is " +
                                    (hub_.set->alone() ? "/api/live" : "/cell/NAME/api/live");
      reply(why.empty() ? 404 : 403, "application/json", error_body(why.empty() ? where : why), false);
      return;
    }
    ++hub_.requests;
    stream_.expires_never();
    std::make_shared<PageSession>(stream_.release_socket(), hub_, *to.api, std::move(slot_))->run(std::move(req));
    return;
  }
  ApiRequest r;
  r.method = std::string(req.method_string());
  r.target = to.target;
  r.host = header(req, http::field::host);
  r.origin = header(req, http::field::origin);
  const auto token = req.find("X-Plc-Token");
  r.token = token == req.end() ? "" : std::string(token->value());
  r.body = std::move(req.body());
  const ApiReply out = hub_.answer(to, r);
  if (out.status >= 400) {
    ++hub_.rejected;
    if (out.status != 404) hub_.note_error(r.method + " " + r.target.substr(0, 200) + ": " + std::to_string(out.status));
  } else {
    ++hub_.requests;
  }
  reply(out.status, out.type, out.body, req.keep_alive());
}

void HttpSession::reply(int status, const std::string& type, std::string body, bool keep_alive) {
  res_ = {};
  res_.result(http::int_to_status(unsigned(status)));
  res_.version(11);
  res_.set(http::field::server, "plc_cell monitor");
  res_.set(http::field::content_type, type);
  res_.set(http::field::cache_control, "no-store");
  res_.set("X-Content-Type-Options", "nosniff");
  res_.keep_alive(keep_alive);
  res_.body() = std::move(body);
  res_.prepare_payload();
  stream_.expires_after(hub_.idle());
  http::async_write(stream_, res_, [self = shared_from_this(), keep_alive](beast::error_code ec, size_t) {
    if (self->slot_) {
      self->slot_->complete();  // the idle time counts from the answer
      self->slot_->waiting(false);
    }
    if (!ec && keep_alive) return self->read();
    beast::error_code ignored;
    self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
  });
}

}  // namespace monitor
}  // namespace plc_cell
