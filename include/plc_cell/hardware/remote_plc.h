#pragma once
// A FATEK or TRi PLC over its host link as a scenario's LinkedPlc: the monitor's remote
// links (remote/fatek_link.h, remote/tri_link.h), which coalesce reads by each protocol's
// poll plan, with forcing as the protocol has it (FATEK's DISABLE and SET/RESET, ENABLE to
// free; the TRi has none).
#include <functional>
#include <memory>
#include <string>

#include "plc_cell/remote/link.h"
#include "plc_cell/scenario/linked_plc.h"

namespace plc_cell {
namespace hardware {

class RemotePlc : public scenario::LinkedPlc {
 public:
  // reach: why an address is not on this PLC ("" = it is).
  RemotePlc(std::unique_ptr<remote::Link> link, std::function<std::string(const Address&)> reach,
            std::string no_mode);
  std::string describe() const override { return link_->describe(); }
  std::string cannot_reach(const Address& a) const override { return reach_(a); }
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override { return link_->read(addrs); }
  std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) override { return link_->forced(bits); }
  void write(const Address& a, uint32_t raw) override { link_->write(a, {raw}); }
  void force(const Address& bit, bool on) override;
  void unforce(const Address& bit) override { link_->force(bit, ForceAction::Enable); }
  std::string cannot_force() const override { return link_->no_forcing(); }
  std::optional<RunMode> mode() override;
  std::string cannot_read_mode() const override { return no_mode_; }

 private:
  std::unique_ptr<remote::Link> link_;
  std::function<std::string(const Address&)> reach_;
  std::string no_mode_;
};

// fatek://HOST:PORT and fatek-serial:DEVICE[:BAUD[:FORMAT]] (the FBs' 9600 7E1 by default).
std::unique_ptr<scenario::LinkedPlc> open_fatek(const std::string& endpoint, int station, int timeout_ms, int retries);
// tri://HOST:PORT and tri-serial:DEVICE[:BAUD[:FORMAT]] (38400 8N1 by default).
std::unique_ptr<scenario::LinkedPlc> open_tri(const std::string& endpoint, int id, int timeout_ms, int retries);

}  // namespace hardware
}  // namespace plc_cell
