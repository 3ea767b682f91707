#pragma once
// The Beast side of the monitor (the only code that includes Boost.Beast): the listener,
// one HTTP session per connection, and a page's WebSocket once it upgrades.
#include <atomic>
#include <chrono>
#include <deque>
#include <list>
#include <memory>
#include <mutex>
#include <string>

#include <boost/asio.hpp>
#include <boost/beast.hpp>

#include "api.h"
#include "feed.h"

namespace plc_cell {
namespace monitor {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

class PageSession;

// What every session shares: the API, the limits, the counters and the open pages. Only
// the io thread touches pages.
struct Hub {
  Hub(const HttpSettings& s) : settings(s) {}
  const HttpSettings& settings;
  std::unique_ptr<Api> api;
  std::atomic<uint64_t> requests{0}, rejected{0}, connections{0};
  mutable std::mutex error_mu;
  std::string last_error;
  std::list<std::weak_ptr<PageSession>> pages;

  std::chrono::steady_clock::duration idle() const { return std::chrono::microseconds(settings.idle_timeout_us); }
  void note_error(const std::string& e) {
    std::lock_guard<std::mutex> lk(error_mu);
    last_error = e;
  }
  void broadcast(const std::string& message);  // to every open page
  void frames_now();                           // every subscribed page sends a frame
};

// Held by a session while its connection counts against max_connections.
struct Slot {
  explicit Slot(Hub& h) : hub(h) { ++hub.connections; }
  ~Slot() { --hub.connections; }
  Slot(const Slot&) = delete;
  Slot& operator=(const Slot&) = delete;
  Hub& hub;
};

class PageSession : public std::enable_shared_from_this<PageSession> {
 public:
  PageSession(tcp::socket socket, Hub& hub, std::unique_ptr<Slot> slot);
  void run(http::request<http::string_body> upgrade);
  void send(std::string message);  // queued; dropped and closed when the page reads nothing
  void send_frame();               // skipped while the page has not taken the last one

 private:
  void on_accept(beast::error_code ec);
  void read();
  void on_message(beast::error_code ec, size_t);
  void write_next();
  void tick_frames();
  void tick_status();
  void tick_idle();
  void close();

  websocket::stream<beast::tcp_stream> ws_;
  Hub& hub_;
  std::unique_ptr<Slot> slot_;
  beast::flat_buffer in_;
  std::deque<std::string> out_;
  bool writing_ = false, closed_ = false;
  std::unique_ptr<Feed> feed_;
  uint64_t program_version_ = 0;
  std::chrono::steady_clock::time_point last_heard_;
  net::steady_timer frame_timer_, status_timer_, idle_timer_;
};

class HttpSession : public std::enable_shared_from_this<HttpSession> {
 public:
  HttpSession(tcp::socket socket, Hub& hub);
  void run() { read(); }

 private:
  void read();
  void on_read(beast::error_code ec, size_t);
  void reply(int status, const std::string& type, std::string body, bool keep_alive);

  beast::tcp_stream stream_;
  Hub& hub_;
  std::unique_ptr<Slot> slot_;
  beast::flat_buffer buffer_;
  std::unique_ptr<http::request_parser<http::string_body>> parser_;
  http::response<http::string_body> res_;
};

}  // namespace monitor
}  // namespace plc_cell
