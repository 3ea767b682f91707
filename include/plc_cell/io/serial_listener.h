#pragma once
// The serial side of the protocol servers (FATEK, TRi), written once, as TcpListener is
// for TCP: one thread owns the line, a wake pipe makes stop() return at once, a device
// that went away (USB adapter unplugged, pty master closed, hang-up) is reopened by path
// until it is back, a request not whole within the frame timeout is dropped. A protocol
// implements SerialProtocol: bytes in, replies out; it never touches the line.
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/io/serial_line.h"

namespace plc_cell {

// Called on the listener's thread only.
class SerialProtocol {
 public:
  virtual ~SerialProtocol() = default;
  // Bytes as they arrive; the replies are appended to out and written back at once.
  // A framing fault found on the way is reported through `fault` (it becomes last_error).
  virtual void feed(const uint8_t* data, size_t n, std::string& out, std::string& fault) = 0;
  // An unfinished request is buffered: its frame timeout runs.
  virtual bool in_frame() const = 0;
  // The unfinished request is dropped: it was not whole within the frame timeout, or the
  // line died under it.
  virtual void drop_frame() = 0;
  // A protocol whose frames end at a silence (Modbus RTU's 3.5 characters, shorter than any
  // frame timeout) says in how many ms it has something to do without new bytes; the
  // listener then calls feed() with none. -1: nothing until bytes come.
  virtual int wake_in_ms() const { return -1; }
};

class SerialListener {
 public:
  SerialListener(SerialProtocol& protocol, SerialSettings line, int frame_timeout_ms);
  ~SerialListener();
  SerialListener(const SerialListener&) = delete;
  SerialListener& operator=(const SerialListener&) = delete;

  // Opens the device and starts the thread; throws plc_cell::Error naming the device.
  void start();
  void stop();

  bool running() const { return running_; }
  bool link_up() const { return link_up_; }
  uint64_t reopened() const { return reopened_; }
  uint64_t frame_timeouts() const { return frame_timeouts_; }
  std::string last_error() const;
  const SerialSettings& settings() const { return line_.settings(); }

 private:
  void loop();
  void deliver(int fd, const uint8_t* data, size_t n);
  bool wait_for_device();  // false once stopping
  void lost(const std::string& why);
  void note(const std::string& e);

  SerialProtocol& protocol_;
  SerialLine line_;
  const int frame_timeout_ms_;
  std::atomic<bool> running_{false};
  std::atomic<bool> link_up_{true};
  std::atomic<uint64_t> reopened_{0};
  std::atomic<uint64_t> frame_timeouts_{0};
  int wake_[2] = {-1, -1};
  mutable std::mutex err_mu_;
  std::string last_error_;
  std::thread thread_;
};

}  // namespace plc_cell
