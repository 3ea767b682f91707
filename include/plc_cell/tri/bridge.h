#pragma once
// The TRi bridge's bus side (no ROS): a host-link master that owns the link to one TRi
// PLC on one thread (io/polled_link.h, as the FATEK bridge). It polls the I/O image (with
// the named signals) and each register group at its rate in the coalesced frames of
// poll_plan.h, reconnects with back-off, and runs the front end's reads, writes, forcing
// and halt/resume between two polls. The TRi has no DISABLE flag: a forced discrete is
// written again by wb at every I/O poll until it is released (docs/tri.md, "tri_bridge").
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/io/polled_link.h"
#include "plc_cell/tri/bridge_config.h"
#include "plc_cell/tri/client.h"
#include "plc_cell/tri/poll_plan.h"

namespace plc_cell {
namespace tri {

class Bridge : public PolledLink {
 public:
  // Called on the bridge's thread; any may be empty. IoResult::run is false after a halt
  // through this bridge (the TRi has no status read).
  struct Sinks {
    std::function<void(const IoResult&)> io;
    std::function<void(const GroupResult&)> group;
    std::function<void(const std::string&)> error;
  };
  // Throws Error on bad settings, a serial line that does not parse or a point not on a TRi.
  Bridge(BridgeConfig cfg, Sinks sinks);
  ~Bridge() override;

  const BridgeConfig& config() const { return cfg_; }
  // Frames of one I/O poll, not counting the forced points it writes again.
  size_t io_frames() const { return io_plan_.requests.size(); }
  // Frames of one poll of group g.
  size_t group_frames(size_t g) const { return groups_.at(g).requests.size(); }
  // Frames sent on the link so far (retries and confirmations included).
  uint64_t frames_sent();

  // Transactions between two polls; each throws Error (CommError, PlcError) and leaves
  // the link to be reconnected when it broke.
  // A signal name of the config, a plc_node address or a TRi name (DM[100], A).
  Address resolve(const std::string& text) const;
  std::vector<uint32_t> read(const Address& start, uint32_t count);
  void write(const Address& start, const std::vector<uint32_t>& raw);
  // Writes the discrete now (wb) and again at every I/O poll until released.
  void force(const Address& bit, bool value);
  // Stops holding bit, or every forced discrete when bit is null (their states stay as
  // they are); returns those that were forced.
  std::vector<Address> release(const Address* bit);
  std::vector<std::pair<Address, bool>> forced() const;
  void set_run(bool run);  // C3 resume, C2 halt

 private:
  Transport& transport() override { return client_->transport(); }
  void confirm() override;
  bool poll_io();
  bool poll_group(size_t g);

  BridgeConfig cfg_;
  Sinks sinks_;
  std::unique_ptr<Client> client_;
  std::vector<PollItem> io_items_;
  PollPlan io_plan_;
  std::vector<PollPlan> groups_;
  mutable std::mutex forced_mu_;
  std::map<uint32_t, std::pair<Address, bool>> forced_;  // by wb address
  bool halted_ = false;  // link lock
};

}  // namespace tri
}  // namespace plc_cell
