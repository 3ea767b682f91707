#include "client.h"

#include <boost/asio.hpp>
#include <boost/beast.hpp>
#include <stdexcept>

namespace plc_cell {
namespace monitor_test {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;
constexpr auto kWait = std::chrono::seconds(5);

std::string default_host(uint16_t port) { return "127.0.0.1:" + std::to_string(port); }

tcp::endpoint at(uint16_t port) { return {net::ip::make_address("127.0.0.1"), port}; }

}  // namespace

HttpReply http_call(uint16_t port, const HttpCall& c) {
  net::io_context ioc;
  beast::tcp_stream stream(ioc);
  HttpReply out;
  http::request<http::string_body> req;
  req.method_string(c.method);
  req.target(c.target);
  req.version(11);
  req.set(http::field::host, c.host.empty() ? default_host(port) : c.host);
  if (!c.origin.empty()) req.set(http::field::origin, c.origin);
  if (!c.token.empty()) req.set("X-Plc-Token", c.token);
  for (const auto& [k, v] : c.headers) req.set(k, v);
  req.body() = c.body;
  req.prepare_payload();
  beast::flat_buffer buf;
  http::response_parser<http::string_body> res;
  res.body_limit(64u << 20);
  stream.expires_after(kWait);
  stream.async_connect(at(port), [&](beast::error_code ec) {
    if (ec) return;
    http::async_write(stream, req, [&](beast::error_code ec, size_t) {
      if (ec) return;
      http::async_read(stream, buf, res, [&](beast::error_code ec, size_t) {
        if (ec) return;
        out.status = int(res.get().result_int());
        out.body = res.get().body();
        out.content_type = std::string(res.get()[http::field::content_type]);
      });
    });
  });
  ioc.run_for(kWait + std::chrono::seconds(1));
  return out;
}

HttpReply http_post(uint16_t port, const std::string& target, const std::string& body, const std::string& token) {
  HttpCall c;
  c.method = "POST";
  c.target = target;
  c.body = body;
  c.token = token;
  c.headers.push_back({"Content-Type", "application/json"});
  return http_call(port, c);
}

std::string raw_exchange(uint16_t port, const std::string& bytes, std::chrono::milliseconds timeout) {
  net::io_context ioc;
  tcp::socket s(ioc);
  std::string got;
  std::array<char, 4096> chunk{};
  std::function<void()> read_more = [&] {
    s.async_read_some(net::buffer(chunk), [&](beast::error_code ec, size_t n) {
      got.append(chunk.data(), n);
      if (!ec && got.size() < (1u << 20)) read_more();
    });
  };
  s.async_connect(at(port), [&](beast::error_code ec) {
    if (ec) return;
    net::async_write(s, net::buffer(bytes), [&](beast::error_code, size_t) {});
    read_more();
  });
  ioc.run_for(timeout);
  return got;
}

bool closed_after_sending(uint16_t port, const std::string& bytes, std::chrono::milliseconds timeout) {
  net::io_context ioc;
  tcp::socket s(ioc);
  bool closed = false;
  std::array<char, 256> chunk{};
  s.async_connect(at(port), [&](beast::error_code ec) {
    if (ec) return;
    if (!bytes.empty()) net::write(s, net::buffer(bytes), ec);
    s.async_read_some(net::buffer(chunk), [&](beast::error_code ec, size_t) {
      closed = bool(ec);
      ioc.stop();
    });
  });
  ioc.run_for(timeout);
  return closed;
}

struct Stallers::Impl {
  net::io_context ioc;
  std::vector<std::unique_ptr<tcp::socket>> sockets;
};

Stallers::Stallers(uint16_t port, size_t n, const std::string& bytes) : impl_(std::make_unique<Impl>()) {
  for (size_t i = 0; i < n; ++i) {
    auto s = std::make_unique<tcp::socket>(impl_->ioc);
    s->connect(at(port));
    net::write(*s, net::buffer(bytes));
    s->non_blocking(true);
    impl_->sockets.push_back(std::move(s));
  }
}

Stallers::~Stallers() = default;

size_t Stallers::open() {
  size_t n = 0;
  for (auto& s : impl_->sockets) {
    std::array<char, 256> chunk{};
    beast::error_code ec;
    s->read_some(net::buffer(chunk), ec);
    n += ec == net::error::would_block;
  }
  return n;
}

struct WsClient::Impl {
  net::io_context ioc;
  websocket::stream<beast::tcp_stream> ws{ioc};
  beast::flat_buffer buf;
  bool closed = false;    // the server closed it
  bool unusable = false;  // a read was cancelled (timeout)
};

WsClient::WsClient(uint16_t port, const std::string& host, const std::string& origin, const std::string& target)
    : impl_(std::make_unique<Impl>()) {
  beast::get_lowest_layer(impl_->ws).expires_after(kWait);
  beast::get_lowest_layer(impl_->ws).connect(at(port));
  const std::string h = host.empty() ? default_host(port) : host;
  const std::string o = origin.empty() ? "http://" + h : origin;
  impl_->ws.set_option(websocket::stream_base::decorator([o](websocket::request_type& r) {
    r.set(http::field::origin, o);
  }));
  beast::get_lowest_layer(impl_->ws).expires_never();
  impl_->ws.handshake(h, target);
}

WsClient::~WsClient() = default;

void WsClient::send(const std::string& text) { impl_->ws.write(net::buffer(text)); }

nlohmann::json WsClient::next(const std::string& type, std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!impl_->closed && !impl_->unusable && std::chrono::steady_clock::now() < deadline) {
    bool done = false;
    impl_->ws.async_read(impl_->buf, [&](beast::error_code ec, size_t) {
      done = true;
      if (ec && ec != net::error::operation_aborted) impl_->closed = true;
    });
    impl_->ioc.restart();
    impl_->ioc.run_until(deadline);
    if (!done) {
      // Timed out: a cancelled WebSocket read leaves the stream unusable.
      beast::get_lowest_layer(impl_->ws).cancel();
      impl_->ioc.restart();
      impl_->ioc.run_for(std::chrono::seconds(1));
      impl_->unusable = !impl_->closed;
      return nullptr;
    }
    if (impl_->closed) return nullptr;
    auto j = nlohmann::json::parse(beast::buffers_to_string(impl_->buf.data()), nullptr, false);
    impl_->buf.consume(impl_->buf.size());
    if (j.is_object() && (type.empty() || j.value("type", "") == type)) return j;
  }
  return nullptr;
}

bool WsClient::closed_within(std::chrono::milliseconds timeout) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (!impl_->closed && !impl_->unusable) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    next("(no such type)", left);
  }
  return impl_->closed;
}

int ws_upgrade(uint16_t port, const std::string& host, const std::string& origin, const std::string& target) {
  HttpCall c;
  c.target = target;
  c.host = host;
  c.origin = origin;
  c.headers = {{"Connection", "Upgrade"},
               {"Upgrade", "websocket"},
               {"Sec-WebSocket-Version", "13"},
               {"Sec-WebSocket-Key", "dGhlIHNhbXBsZSBub25jZQ=="}};
  return http_call(port, c).status;
}

}  // namespace monitor_test
}  // namespace plc_cell
