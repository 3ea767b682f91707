#include "json_views.h"
#include "plc_cell/core/error.h"
#include "sessions.h"

namespace plc_cell {
namespace monitor {
namespace {
// Messages waiting for a page that does not read: past this, the page is dropped.
constexpr size_t kMaxQueued = 256;
}  // namespace

PageSession::PageSession(tcp::socket socket, Hub& hub, Api& api, std::unique_ptr<Slot> slot)
    : ws_(std::move(socket)),
      hub_(hub),
      api_(api),
      slot_(std::move(slot)),
      last_heard_(std::chrono::steady_clock::now()),
      frame_timer_(ws_.get_executor()),
      status_timer_(ws_.get_executor()),
      idle_timer_(ws_.get_executor()) {}

void PageSession::run(http::request<http::string_body> upgrade) {
  ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
  ws_.read_message_max(kMaxBody);
  ws_.async_accept(upgrade, beast::bind_front_handler(&PageSession::on_accept, shared_from_this()));
}

void PageSession::on_accept(beast::error_code ec) {
  if (ec) return;
  hub_.pages.push_back(weak_from_this());
  // Not waiting until it subscribes: a page that never does may lose its slot to a new client.
  slot_->owner(weak_from_this());
  slot_->waiting(false);
  try {
    program_version_ = api_.ladder()->program().version;
  } catch (const std::exception& e) {
    send(dump({{"type", "error"}, {"error", e.what()}}));
  }
  tick_status();
  tick_idle();
  read();
}

void PageSession::read() {
  ws_.async_read(in_, beast::bind_front_handler(&PageSession::on_message, shared_from_this()));
}

void PageSession::on_message(beast::error_code ec, size_t) {
  if (ec) {
    if (ec == websocket::error::message_too_big)
      send(dump({{"type", "error"}, {"error", "message over the limit of 65536 bytes"}}));
    return close();
  }
  last_heard_ = std::chrono::steady_clock::now();
  slot_->complete();
  const std::string text = beast::buffers_to_string(in_.data());
  in_.consume(in_.size());
  const auto j = nlohmann::json::parse(text, nullptr, false);
  try {
    if (j.is_discarded()) throw Error("the message is not JSON");
    const bool first = !feed_;
    feed_ = std::make_unique<Feed>(parse_subscription(j, *api_.ladder(), api_.set(), api_.self()), api_.ladder(), feed_.get());
    slot_->waiting(true);  // it receives frames: it keeps its slot
    ++hub_.requests;
    if (first) tick_frames();
    else send_frame();  // the new subscription at once; the timer keeps its new rate
  } catch (const std::exception& e) {
    ++hub_.rejected;
    send(dump({{"type", "error"}, {"error", e.what()}}));
  }
  read();
}

void PageSession::send(std::string message) {
  if (closed_) return;
  if (out_.size() >= kMaxQueued) return close();
  out_.push_back(std::move(message));
  if (!writing_) write_next();
}

void PageSession::send_frame() {
  if (!feed_ || closed_ || !out_.empty()) return;  // a slow page gets fewer frames, not a backlog
  try {
    send(dump(feed_->frame(api_.source())));
    api_.note_read(feed_->failure());
  } catch (const std::exception& e) {
    send(dump({{"type", "error"}, {"error", e.what()}}));
  }
}

void PageSession::write_next() {
  if (out_.empty() || closed_) {
    writing_ = false;
    return;
  }
  writing_ = true;
  ws_.text(true);
  ws_.async_write(net::buffer(out_.front()), [self = shared_from_this()](beast::error_code ec, size_t) {
    if (ec) return self->close();
    self->out_.pop_front();
    self->write_next();
  });
}

void PageSession::tick_frames() {
  if (closed_ || !feed_) return;
  send_frame();
  frame_timer_.expires_after(std::chrono::microseconds(1'000'000 / feed_->subscription().rate_hz));
  frame_timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (!ec) self->tick_frames();
  });
}

void PageSession::tick_status() {
  if (closed_) return;
  try {
    send(dump(api_.status_message()));
    const uint64_t v = api_.ladder()->program().version;
    if (v != program_version_) {
      program_version_ = v;
      send(dump({{"type", "program"}, {"version", v}}));
    }
  } catch (const std::exception& e) {
    send(dump({{"type", "error"}, {"error", e.what()}}));
  }
  status_timer_.expires_after(std::chrono::seconds(1));
  status_timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (!ec) self->tick_status();
  });
}

// A page that subscribed receives frames and is not idle; one that never subscribed and
// sent nothing for idle_timeout is closed.
void PageSession::tick_idle() {
  if (closed_) return;
  const auto now = std::chrono::steady_clock::now();
  if (!feed_ && now - last_heard_ >= hub_.idle()) return close();
  idle_timer_.expires_at(feed_ ? now + hub_.idle() : last_heard_ + hub_.idle());
  idle_timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
    if (!ec) self->tick_idle();
  });
}

void PageSession::close() {
  if (closed_) return;
  closed_ = true;
  frame_timer_.cancel();
  status_timer_.cancel();
  idle_timer_.cancel();
  beast::error_code ignored;
  beast::get_lowest_layer(ws_).socket().shutdown(tcp::socket::shutdown_both, ignored);
  beast::get_lowest_layer(ws_).socket().close(ignored);
}

}  // namespace monitor
}  // namespace plc_cell
