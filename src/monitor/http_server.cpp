#include "plc_cell/monitor/http_server.h"

#include <cstdlib>
#include <random>
#include <sys/stat.h>
#include <thread>

#include "plc_cell/core/error.h"
#include "plc_cell/io/serial_settings.h"
#include "sessions.h"

namespace plc_cell {
namespace monitor {
namespace {

std::string random_token() {
  std::random_device rd;
  static const char digits[] = "0123456789abcdef";
  std::string t;
  for (int i = 0; i < 32; ++i) t += digits[rd() % 16];
  return t;
}

bool is_dir(const std::string& p) {
  struct stat st {};
  return !p.empty() && ::stat(p.c_str(), &st) == 0 && S_ISDIR(st.st_mode);
}

}  // namespace

std::string default_asset_root() {
  if (const char* env = std::getenv("PLC_CELL_MONITOR_ASSETS"); env && *env) return env;
#ifdef PLC_CELL_MONITOR_SOURCE_ASSETS
  if (is_dir(PLC_CELL_MONITOR_SOURCE_ASSETS)) return PLC_CELL_MONITOR_SOURCE_ASSETS;
#endif
#ifdef PLC_CELL_MONITOR_INSTALLED_ASSETS
  if (is_dir(PLC_CELL_MONITOR_INSTALLED_ASSETS)) return PLC_CELL_MONITOR_INSTALLED_ASSETS;
#endif
  return "";
}

HttpSettings http_settings(const Settings& v) {
  HttpSettings s;
  s.endpoint = v.text("tcp");
  s.writable = v.writable("writable");
  s.max_connections = int(v.integer("max_connections"));
  s.idle_timeout_us = v.duration_us("idle_timeout");
  for (const auto& h : v.all("allowed_hosts"))
    if (!h.empty()) s.allowed_hosts.push_back(h);
  s.asset_root = v.text("assets");
  s.edit = v.boolean("edit");
  return s;
}

class HttpServer::Impl {
 public:
  Impl(SourceSet set, HttpSettings settings) : set_(std::move(set)), settings_(std::move(settings)), hub_(settings_) {
    if (set_.size() == 0) throw Error("monitor " + settings_.endpoint + ": no cell to serve");
    hub_.set = &set_;
    parse_host_port(settings_.endpoint, &host_, &port_);
    if (host_.empty()) host_ = "127.0.0.1";
  }
  ~Impl() { stop(); }

  void start();
  void stop();
  void accept();
  void admit(tcp::socket socket);
  std::string url() const {
    const bool v6 = host_.find(':') != std::string::npos;
    return "http://" + (v6 ? "[" + host_ + "]" : host_) + ":" + std::to_string(port_) + "/";
  }
  ServerStatus status() const {
    ServerStatus s;
    s.running = running_;
    s.requests = hub_.requests;
    s.rejected = hub_.rejected;
    s.connections = hub_.connections;
    std::lock_guard<std::mutex> lk(hub_.error_mu);
    s.last_error = hub_.last_error;
    return s;
  }

  // Every cell of a recording shows one instant: a move of one cursor moves the others to it.
  void follow_cursor(size_t moved) {
    Replay* r = set_.source(moved).replay();
    if (!r) return;
    for (size_t i = 0; i < set_.size(); ++i)
      if (Replay* o = set_.source(i).replay(); i != moved && o) o->seek(r->cursor_us());
  }

  SourceSet set_;
  HttpSettings settings_;
  std::string host_;
  int port_ = 0;
  std::string token_ = random_token();
  std::atomic<bool> running_{false};
  Hub hub_;  // before the io_context: sessions destroyed with it still count down here
  // One of each per start: stop() destroys the io_context with the handlers it still
  // holds, and with them the sessions (their connections close), so that a start after a
  // stop begins as the first did.
  std::unique_ptr<net::io_context> ioc_;
  std::unique_ptr<tcp::acceptor> acceptor_;
  std::thread thread_;
};

void HttpServer::Impl::start() {
  if (running_) return;
  ioc_ = std::make_unique<net::io_context>(1);
  acceptor_ = std::make_unique<tcp::acceptor>(*ioc_);
  hub_.apis.clear();
  for (size_t i = 0; i < set_.size(); ++i) {
    Api::Events events{[this, i](const std::string& m) {
                         net::post(*ioc_, [this, i, m] { hub_.broadcast(hub_.apis[i].get(), m); });
                       },
                       [this, i] {
                         follow_cursor(i);
                         net::post(*ioc_, [this] { hub_.frames_now(); });
                       }};
    hub_.apis.push_back(std::make_unique<Api>(set_.source(i), settings_, host_, token_, std::move(events)));
    hub_.apis.back()->serve_in(&set_, i);
  }
  hub_.overview = std::make_unique<Overview>(set_, hub_.apis, settings_);
  try {
    tcp::resolver resolver(*ioc_);
    const auto found = *resolver.resolve(host_, std::to_string(port_)).begin();
    acceptor_->open(found.endpoint().protocol());
    acceptor_->set_option(net::socket_base::reuse_address(true));
    acceptor_->bind(found.endpoint());
    acceptor_->listen(net::socket_base::max_listen_connections);
    port_ = acceptor_->local_endpoint().port();  // a start after a stop binds this port again
  } catch (const std::exception& e) {
    acceptor_.reset();
    ioc_.reset();
    throw Error("monitor " + settings_.endpoint + ": cannot listen: " + e.what());
  }
  running_ = true;
  accept();
  thread_ = std::thread([this] {
    // A handler that throws (a source failing where no one expected it) costs its session,
    // never the server.
    for (;;) {
      try {
        ioc_->run();
        return;
      } catch (const std::exception& e) {
        hub_.note_error(e.what());
      }
    }
  });
}

void HttpServer::Impl::accept() {
  acceptor_->async_accept(net::make_strand(*ioc_), [this](beast::error_code ec, tcp::socket socket) {
    if (ec == net::error::operation_aborted || !acceptor_->is_open()) return;
    if (!ec) admit(std::move(socket));
    accept();
  });
}

// A full table gives the slot of the connection that has gone longest without completing a
// request to the new one (io/connections.h); only when every connection is busy (a page
// receiving frames, a request being answered) is the new one refused.
void HttpServer::Impl::admit(tcp::socket socket) {
  int evicted_fd = -1;
  std::weak_ptr<Closable> evicted;
  const auto how = hub_.table.admit(int(socket.native_handle()), std::chrono::steady_clock::now(), &evicted_fd, &evicted);
  if (how == Connections<std::weak_ptr<Closable>>::Admit::Refused) {
    std::make_shared<HttpSession>(std::move(socket), hub_, nullptr)->run();
    return;
  }
  if (auto stale = evicted.lock()) stale->evict();
  auto slot = std::make_unique<Slot>(hub_, hub_.table.all().back().id);
  std::make_shared<HttpSession>(std::move(socket), hub_, std::move(slot))->run();
}

void HttpServer::Impl::stop() {
  if (!running_) return;
  ioc_->stop();
  if (thread_.joinable()) thread_.join();
  acceptor_.reset();
  ioc_.reset();
  running_ = false;
}

namespace {
// A lone cell is the set of one; its page stays at / (cell_routes.h).
SourceSet lone(Source& source) {
  SourceSet set;
  set.add("cell", source);
  set.serve_alone();
  return set;
}
}  // namespace

HttpServer::HttpServer(Source& source, HttpSettings settings)
    : impl_(std::make_unique<Impl>(lone(source), std::move(settings))) {}

HttpServer::HttpServer(std::unique_ptr<Source> source, HttpSettings settings)
    : owned_(std::move(source)), impl_(std::make_unique<Impl>(lone(*owned_), std::move(settings))) {}

HttpServer::HttpServer(SourceSet set, HttpSettings settings)
    : impl_(std::make_unique<Impl>(std::move(set), std::move(settings))) {}

HttpServer::~HttpServer() { impl_.reset(); }

void HttpServer::start() { impl_->start(); }
void HttpServer::stop() { impl_->stop(); }
std::string HttpServer::describe() const { return "monitor " + impl_->url(); }
ServerStatus HttpServer::status() const { return impl_->status(); }
uint16_t HttpServer::port() const { return uint16_t(impl_->port_); }
const std::string& HttpServer::token() const { return impl_->token_; }

}  // namespace monitor
}  // namespace plc_cell
