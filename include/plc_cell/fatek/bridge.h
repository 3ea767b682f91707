#pragma once
// The FATEK bridge's bus side (no ROS): one thread owns the link to one PLC station
// (io/polled_link.h). It polls the I/O image (with the named signals) and each register
// group at its rate, in the coalesced frames of poll_plan.h, reconnects with back-off, and
// runs the front end's reads, writes and forcing between two polls: a FATEK line is
// half-duplex, so there is one transaction at a time.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/fatek/bridge_config.h"
#include "plc_cell/fatek/client.h"
#include "plc_cell/fatek/poll_plan.h"
#include "plc_cell/io/polled_link.h"

namespace plc_cell {
namespace fatek {

using plc_cell::LinkStatus;

using plc_cell::GroupResult;
using plc_cell::IoResult;  // run: the RUN bit (cmd 40)

class Bridge : public PolledLink {
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

  // start(), stop(), recover(), status(), describe(): PolledLink's.
  const BridgeConfig& config() const { return cfg_; }
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
  // Which of bits are forced (disabled) now: command 43, one frame per run of neighbours.
  std::vector<bool> forced(const std::vector<Address>& bits);
  void set_run(bool run);  // 41

 private:
  Transport& transport() override { return client_->transport(); }
  void confirm() override { client_->loopback("PLC"); }
  bool poll_io();
  bool poll_group(size_t g);

  BridgeConfig cfg_;
  Sinks sinks_;
  std::unique_ptr<Client> client_;
  std::vector<PollItem> io_items_;
  PollPlan io_plan_;
  struct Group {
    std::vector<PollItem> items;
    PollPlan plan;
  };
  std::vector<Group> groups_;
};

}  // namespace fatek
}  // namespace plc_cell
