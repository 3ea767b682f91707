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
#include "cell_routes.h"
#include "feed.h"
#include "overview.h"
#include "plc_cell/io/connections.h"

namespace plc_cell {
namespace monitor {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

class PageSession;

// A connection the cap may close to make room for a new one (Connections::admit).
class Closable {
 public:
  virtual ~Closable() = default;
  virtual void evict() = 0;
};

// What every session shares: each cell's API and the overview, the limits, the counters,
// the open pages and the connections' table (io/connections.h: when every slot is taken, a
// new client takes the slot of the connection that has gone longest without completing a
// request). Only the io thread touches pages and the table.
struct Hub {
  explicit Hub(const HttpSettings& s);
  const HttpSettings& settings;
  const SourceSet* set = nullptr;
  std::vector<std::unique_ptr<Api>> apis;  // one per cell of the set, in its order
  std::unique_ptr<Overview> overview;
  std::atomic<uint64_t> requests{0}, rejected{0}, connections{0};
  mutable std::mutex error_mu;
  std::string last_error;
  std::list<std::weak_ptr<PageSession>> pages;
  Connections<std::weak_ptr<Closable>> table;

  std::chrono::steady_clock::duration idle() const { return std::chrono::microseconds(settings.idle_timeout_us); }
  std::chrono::steady_clock::duration header_time() const {
    return std::chrono::microseconds(settings.header_timeout_us);
  }
  void note_error(const std::string& e) {
    std::lock_guard<std::mutex> lk(error_mu);
    last_error = e;
  }
  void broadcast(const Api* cell, const std::string& message);  // to every open page of the cell
  void frames_now();                           // every subscribed page sends a frame
  // A request not upgraded to a WebSocket, routed: its cell's Api's answer, the overview's,
  // or 404 saying why.
  ApiReply answer(const Route& to, const ApiRequest& r);
  // The table's entry of a connection (nullptr once it is out of the table).
  Connections<std::weak_ptr<Closable>>::Conn* conn(uint64_t id);
};

// A connection's place in the table, held by its session (the HTTP session, then the page
// it became); leaving it frees the slot.
class Slot {
 public:
  Slot(Hub& h, uint64_t id) : hub_(h), id_(id) { ++hub_.connections; }
  ~Slot();
  Slot(const Slot&) = delete;
  Slot& operator=(const Slot&) = delete;
  void owner(std::weak_ptr<Closable> c);  // who evict() reaches
  void partial();                          // bytes of a request came: its deadline runs
  void complete();                         // a whole request came
  void waiting(bool w);                    // work is out for it (a reply, a page's frames)

 private:
  Hub& hub_;
  uint64_t id_;
};

class PageSession : public Closable, public std::enable_shared_from_this<PageSession> {
 public:
  PageSession(tcp::socket socket, Hub& hub, Api& api, std::unique_ptr<Slot> slot);
  const Api* api() const { return &api_; }
  void evict() override { close(); }
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
  Api& api_;  // the page's cell
  std::unique_ptr<Slot> slot_;
  beast::flat_buffer in_;
  std::deque<std::string> out_;
  bool writing_ = false, closed_ = false;
  std::unique_ptr<Feed> feed_;
  uint64_t program_version_ = 0;
  std::chrono::steady_clock::time_point last_heard_;
  net::steady_timer frame_timer_, status_timer_, idle_timer_;
};

class HttpSession : public Closable, public std::enable_shared_from_this<HttpSession> {
 public:
  // slot: its place in the table; nullptr when the table refused it (answered 503).
  HttpSession(tcp::socket socket, Hub& hub, std::unique_ptr<Slot> slot);
  void run();
  void evict() override;

 private:
  void read();
  void on_first_bytes();
  void on_header(beast::error_code ec);
  void on_read(beast::error_code ec, size_t);
  void end(beast::error_code ec);
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
