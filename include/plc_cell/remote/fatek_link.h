#pragma once
// A FATEK FBs-PLC over its host link (fatek/client.h), as a remote monitor link: reads
// coalesced by fatek/poll_plan.h (runs of one area in 44/46 block frames, the rest in 48
// mixed frames), RUN/STOP read with command 40 and set with 41, forcing with 42
// (DISABLE/ENABLE, SET/RESET) and the forced points read with 43 (runs of one area, up to
// 256 points a frame, short gaps read through).
#include <memory>
#include <string>

#include "plc_cell/fatek/client.h"
#include "plc_cell/remote/link.h"

namespace plc_cell {
namespace remote {

struct FatekLinkOptions {
  std::string endpoint;  // HOST:PORT, or DEVICE[:BAUD[:FORMAT]] for a serial line
  int station = 1;
  int timeout_ms = 1000;
  int retries = 0;  // a monitor asks again at its next frame anyway
};

class FatekLink : public Link {
 public:
  // Throws Error for an endpoint client_transport refuses (io/endpoint.h). Connects at the
  // first transaction.
  explicit FatekLink(const FatekLinkOptions& opt);
  std::string describe() const override { return name_; }
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override;
  std::optional<RunMode> mode() override;
  void write(const Address& start, const std::vector<uint32_t>& values) override;
  void force(const Address& bit, ForceAction action) override;
  std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) override;
  void set_run(bool run) override { client_->set_run(run); }
  bool can_set_mode() const override { return true; }
  uint64_t frames() const override { return frames_; }
  uint64_t last_latency_us() const override { return client_->last_latency_us(); }

 private:
  std::string name_;
  std::unique_ptr<fatek::Client> client_;
  uint64_t frames_ = 0;
};

}  // namespace remote
}  // namespace plc_cell
