#pragma once
// The TCP side of the protocol servers (FATEK, Modbus), written once: a listening socket
// (127.0.0.1 unless told otherwise), one thread with a poll() loop over it and the
// clients, a wake pipe so stop() returns at once, the connection table and time bounds
// of io/connections.h, per-connection input and output buffers, and bounded output (a
// client that leaves its replies unread is dropped). A protocol server implements
// TcpProtocol: it turns buffered bytes into replies and counts what it sees; it never
// touches a socket, so a client can only ever cost it the bytes it sent.
#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "plc_cell/io/connections.h"

namespace plc_cell {

// Called on the listener's thread only.
class TcpProtocol {
 public:
  virtual ~TcpProtocol() = default;

  // What the protocol keeps per connection besides its bytes (a streaming decoder).
  struct Session {
    virtual ~Session() = default;
  };
  virtual std::unique_ptr<Session> open() { return nullptr; }

  struct Taken {
    int requests = 0;      // whole requests taken: the idle deadline restarts
    bool partial = false;  // an unfinished request is buffered: its frame deadline runs
    bool bad = false;      // the stream cannot be resynchronised: the connection is closed
    bool waiting = false;  // the last request is answered later, by TcpListener::deliver()
  };
  // Takes zero or more whole requests from the front of `in` (erasing them) and appends
  // their replies to `out`. While it takes requests, the replies go out and it is called
  // again: a protocol that must not execute a request after its predecessor's reply
  // failed takes one at a time. A protocol that keeps bytes of its own (a decoder) may
  // take all of `in`. It must not leave max_input bytes untaken without saying bad.
  virtual Taken take(uint64_t conn, Session* session, std::string& in, std::string& out) = 0;

  enum class Event {
    Refused,           // a new client found every slot taken and none evictable
    Evicted,           // a connection gave its slot to a new client (no request for frame_timeout)
    FrameTimeout,      // a request not whole within frame_timeout: closed
    ClosedMidRequest,  // the peer closed with an unfinished request buffered
    ReplyFailed,       // send() failed (err): closed
    SlowReader,        // more than max_pending_output left unsent (err: send()'s errno): closed
  };
  virtual void on_event(Event e, int err) = 0;
  virtual void on_connections(size_t open) { (void)open; }
};

struct TcpListenerOptions {
  std::string name = "TCP";         // errors read "<name> HOST:PORT: ..."
  std::string host = "127.0.0.1";   // empty: 127.0.0.1
  int port = 0;                     // 0: any free port; see port()
  ConnectionLimits limits;
  size_t max_input = 4096;          // bytes buffered per connection (and read per recv)
  size_t max_pending_output = 0;    // 0: a reply must fit the socket buffer at once
};

class TcpListener {
 public:
  TcpListener(TcpProtocol& protocol, TcpListenerOptions opt);
  ~TcpListener();
  TcpListener(const TcpListener&) = delete;
  TcpListener& operator=(const TcpListener&) = delete;

  // Binds and starts the thread; throws plc_cell::Error naming the endpoint.
  void start();
  void stop();
  bool running() const { return running_; }
  int port() const { return bound_port_; }  // the real port after start()
  const TcpListenerOptions& options() const { return opt_; }

  // Thread-safe: the reply to the request take() left waiting on connection conn. It is
  // sent, and the requests buffered meanwhile are taken; dropped if conn has gone.
  void deliver(uint64_t conn, std::string reply);

 private:
  void loop();

  TcpProtocol& protocol_;
  TcpListenerOptions opt_;
  int listen_fd_ = -1;
  int wake_[2] = {-1, -1};
  int bound_port_ = 0;
  std::thread thread_;
  std::atomic<bool> running_{false};
  std::mutex done_mu_;
  std::vector<std::pair<uint64_t, std::string>> done_;
};

}  // namespace plc_cell
