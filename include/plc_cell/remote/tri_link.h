#pragma once
// A TRi PLC over its host link (tri/client.h), as a remote monitor link: reads coalesced by
// tri/poll_plan.h (discretes by words of 16, ADC and EEPROM runs; every other element is a
// frame of its own, the TRi having no multi-word read of them), writes by plan_write, RUN
// and STOP by the manual's Halt (C2) and Resume (C3). The TRi reports no RUN/STOP state and
// has no DISABLE flag: mode() is what this link last set, and forcing is refused.
#include <memory>
#include <optional>
#include <string>

#include "plc_cell/remote/link.h"
#include "plc_cell/tri/client.h"

namespace plc_cell {
namespace remote {

struct TriLinkOptions {
  std::string endpoint;  // HOST:PORT, or DEVICE[:BAUD[:FORMAT]] (38400 8N1 when only DEVICE)
  int id = 1;
  int timeout_ms = 1000;
  int retries = 0;
};

class TriLink : public Link {
 public:
  // Throws Error for an endpoint client_transport refuses (io/endpoint.h). Connects at the
  // first transaction.
  explicit TriLink(const TriLinkOptions& opt);
  std::string describe() const override { return name_; }
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override;
  std::optional<RunMode> mode() override { return mode_; }
  void write(const Address& start, const std::vector<uint32_t>& values) override;
  void force(const Address& bit, ForceAction action) override;
  std::optional<std::vector<bool>> forced(const std::vector<Address>&) override { return std::nullopt; }
  std::string no_forcing() const override;
  void set_run(bool run) override;
  bool can_set_mode() const override { return true; }
  uint64_t frames() const override { return client_->requests(); }
  uint64_t last_latency_us() const override { return client_->last_latency_us(); }

 private:
  std::string name_;
  std::unique_ptr<tri::Client> client_;
  std::optional<RunMode> mode_;  // as last set through this link
};

}  // namespace remote
}  // namespace plc_cell
