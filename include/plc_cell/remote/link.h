#pragma once
// One real PLC's host link as the remote monitor source uses it (remote_source.h): the
// values of a list of addresses read in as few frames as the protocol allows, and the
// protocol's own commands for writing, forcing and RUN/STOP where it has them. Each
// transaction is bounded by the link's time-out; every failure throws plc_cell::Error
// (CommError for a dead or silent link). One transaction at a time: the caller serialises.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {
namespace remote {

class Link {
 public:
  virtual ~Link() = default;
  virtual std::string describe() const = 0;  // "FATEK 127.0.0.1:500 station 1"
  // One value per address (as Plc::read gives it), read in coalesced frames.
  virtual std::vector<uint32_t> read(const std::vector<Address>& addrs) = 0;
  // RUN or STOP as the PLC reports it; nullopt when the protocol cannot read it.
  virtual std::optional<RunMode> mode() = 0;
  virtual void write(const Address& start, const std::vector<uint32_t>& values) = 0;
  virtual void force(const Address& bit, ForceAction action) = 0;
  // Which of bits (single discretes) are forced (DISABLEd) in the PLC, read in as few frames
  // as the protocol allows; nullopt when the protocol cannot tell.
  virtual std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) = 0;
  // Why force() cannot work on this protocol ("" = it can).
  virtual std::string no_forcing() const { return ""; }
  virtual void set_run(bool run) = 0;
  // Whether set_run and force can work on this protocol (the page offers them or not).
  virtual bool can_set_mode() const = 0;
  // Frames sent so far, retries included: what the polls cost on the line.
  virtual uint64_t frames() const = 0;
  virtual uint64_t last_latency_us() const = 0;
};

}  // namespace remote
}  // namespace plc_cell
