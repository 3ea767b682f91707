#include "json_views.h"
#include "sessions.h"

namespace plc_cell {
namespace monitor {

void Hub::broadcast(const std::string& message) {
  for (auto it = pages.begin(); it != pages.end();) {
    if (auto p = it->lock()) {
      p->send(message);
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

HttpSession::HttpSession(tcp::socket socket, Hub& hub)
    : stream_(std::move(socket)), hub_(hub), slot_(std::make_unique<Slot>(hub)) {}

void HttpSession::read() {
  if (hub_.connections > uint64_t(hub_.settings.max_connections)) {
    ++hub_.rejected;
    reply(503, "application/json",
          error_body("too many connections (max_connections " + std::to_string(hub_.settings.max_connections) + ")"),
          false);
    return;
  }
  parser_ = std::make_unique<http::request_parser<http::string_body>>();
  parser_->header_limit(16 * 1024);
  parser_->body_limit(kMaxBody);
  stream_.expires_after(hub_.idle());
  http::async_read(stream_, buffer_, *parser_, beast::bind_front_handler(&HttpSession::on_read, shared_from_this()));
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
      ec == net::error::connection_reset || ec == net::error::operation_aborted) {
    beast::error_code ignored;
    stream_.socket().shutdown(tcp::socket::shutdown_both, ignored);
    return;
  }
  if (ec) {
    ++hub_.rejected;
    const std::string why = ec == http::error::body_limit ? "request body over the limit of 65536 bytes"
                            : ec == http::error::header_limit ? "request header over the limit of 16384 bytes"
                                                                : "malformed HTTP request: " + ec.message();
    reply(parse_error_status(ec), "application/json", error_body(why), false);
    return;
  }
  auto req = parser_->release();
  if (websocket::is_upgrade(req)) {
    const std::string why = hub_.api->refusal({"GET", "", header(req, http::field::host), header(req, http::field::origin), "", ""});
    if (!why.empty() || req.target() != "/api/live") {
      ++hub_.rejected;
      reply(why.empty() ? 404 : 403, "application/json",
            error_body(why.empty() ? std::string(req.target()) + ": the WebSocket is /api/live" : why), false);
      return;
    }
    ++hub_.requests;
    stream_.expires_never();
    std::make_shared<PageSession>(stream_.release_socket(), hub_, std::move(slot_))->run(std::move(req));
    return;
  }
  ApiRequest r;
  r.method = std::string(req.method_string());
  r.target = std::string(req.target());
  r.host = header(req, http::field::host);
  r.origin = header(req, http::field::origin);
  const auto token = req.find("X-Plc-Token");
  r.token = token == req.end() ? "" : std::string(token->value());
  r.body = std::move(req.body());
  const ApiReply out = hub_.api->handle(r);
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
    if (!ec && keep_alive) return self->read();
    beast::error_code ignored;
    self->stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
  });
}

}  // namespace monitor
}  // namespace plc_cell
