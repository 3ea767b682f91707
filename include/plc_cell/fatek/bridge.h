#pragma once
// The FATEK bridge's bus side (no ROS): one thread owns the link to one PLC station. It
// polls the I/O image (with the named signals) and each register group at its rate, in
// the coalesced frames of poll_plan.h, reconnects with back-off (io/backoff.h), and runs
// the front end's reads, writes and forcing between two polls: a FATEK line is
// half-duplex, so there is one transaction at a time.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/bridge_config.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/poll_plan.h"

namespace plc_cell {
namespace fatek {

struct LinkStatus {
  bool connected = false;
  std::string last_error;  // "" until something fails, and after recover()
  uint64_t errors = 0, polls = 0, reconnects = 0;
  double latency_last_ms = 0, latency_max_ms = 0;  // of an I/O poll (status + image)
};

// One poll of the I/O image: the RUN bit (cmd 40), X0..X255, Y0..Y255 and each signal.
struct IoResult {
  bool ok = false;
  std::string error;
  bool run = false;
  std::vector<bool> x, y;    // 256 each
  std::vector<bool> signals;  // per BridgeConfig::signals
};

// One poll of one register group: every element of its spans, in their order.
struct GroupResult {
  size_t group = 0;
  bool ok = false;
  std::string error;
  std::vector<uint32_t> values;
};

class Bridge {
 public:
  // Called on the bridge's thread; any may be empty.
  struct Sinks {
    std::function<void(const IoResult&)> io;        // every I/O poll, failed ones too (ok = false)
    std::function<void(const GroupResult&)> group;  // every group poll, failed ones too
    std::function<void(const std::string&)> error;  // every failure counted in status().errors
  };
  // Throws Error on bad settings (check_link_settings) or a serial line that does not parse.
  Bridge(BridgeConfig cfg, Sinks sinks);
  ~Bridge();

  void start();
  void stop();
  // Drops the link and reconnects now, back-off reset.
  void recover();
  LinkStatus status() const;
  const BridgeConfig& config() const { return cfg_; }
  // "TCP 127.0.0.1:500 station 1"
  const std::string& describe() const { return link_name_; }
  // Frames of one I/O poll (the status frame included).
  size_t io_frames() const { return io_plan_.requests.size() + 1; }

  // Transactions between two polls; each throws Error (CommError, PlcError) and leaves
  // the link to be reconnected when it broke.
  // A signal name of the config, or an address (X3, R100, DR4088).
  Address resolve(const std::string& text) const;
  std::vector<uint32_t> read(const Address& start, uint32_t count);  // 44 or 46
  void write(const Address& start, const std::vector<uint32_t>& raw);  // 45 or 47
  // Locks a discrete at value: 42 DISABLE, then SET or RESET.
  void force(const Address& bit, bool value);
  // Frees bit, or every locked discrete when bit is null (43 finds them, 42 ENABLE frees
  // each); returns those that were locked.
  std::vector<Address> release(const Address* bit);
  void set_run(bool run);  // 41

 private:
  using Clock = std::chrono::steady_clock;
  struct Group {
    std::vector<PollItem> items;
    PollPlan plan;
    Clock::duration period;
    Clock::time_point due;
  };
  void run();
  bool connect_locked();
  bool poll_io();
  bool poll_group(size_t g);
  void fail(const std::string& what);
  void drop_link();
  template <typename F>
  auto transaction(F&& f) -> decltype(f());
  template <typename F>
  bool polled(std::string* error, F&& body);

  BridgeConfig cfg_;
  Sinks sinks_;
  std::unique_ptr<Client> client_;
  std::string link_name_;
  std::vector<PollItem> io_items_;
  PollPlan io_plan_;
  Clock::duration io_period_;
  Clock::time_point io_due_;
  std::vector<Group> groups_;

  std::mutex link_mu_;  // one transaction at a time on the half-duplex link
  mutable std::mutex state_mu_;
  std::condition_variable cv_;
  bool stopping_ = false, recover_ = false;
  LinkStatus status_;
  std::thread thread_;
};

}  // namespace fatek
}  // namespace plc_cell
