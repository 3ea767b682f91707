#pragma once
// A PLC that a scenario reaches over a link, in wall-clock time: a real FATEK, TRi or Modbus
// PLC through its host link (the hardware layer), or a cell on ROS through its node's
// topics and services. What a wall-clock target (wall_clock_target.h) needs of it: reads in
// as few transactions as the link allows, writes, the protocol's own forcing where it has
// one, and what it cannot do, said once so that a scenario is refused before it starts.
//
// Every call is one or more transactions bounded by the link's time-out. A dead, silent
// or garbling link throws CommError (io/transport.h); the PLC refusing a request throws
// Error saying why. One transaction at a time: the caller serialises.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/io/transport.h"

namespace plc_cell {
namespace scenario {

class LinkedPlc {
 public:
  virtual ~LinkedPlc() = default;
  // "FATEK 127.0.0.1:500 station 1"
  virtual std::string describe() const = 0;
  // Why a is out of this PLC's reach over this link ("" = it can be read and written).
  virtual std::string cannot_reach(const Address& a) const = 0;
  // One value per address, as Plc::read gives it.
  virtual std::vector<uint32_t> read(const std::vector<Address>& addrs) = 0;
  // Which of bits (single discretes) are forced; nullopt when the link cannot tell.
  virtual std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) = 0;
  // One element, its raw bits (encode_element's form).
  virtual void write(const Address& a, uint32_t raw) = 0;
  // Locks bit at on against the program and the input refresh (FATEK: DISABLE, then SET or
  // RESET), and frees it (ENABLE), leaving its state as it is.
  virtual void force(const Address& bit, bool on) = 0;
  virtual void unforce(const Address& bit) = 0;
  // Why this link cannot lock a point ("" = it can): then an input it writes lasts only
  // until the PLC's next input refresh.
  virtual std::string cannot_force() const = 0;
  // RUN or STOP as the PLC reports it; nullopt when the link cannot tell (then
  // cannot_read_mode() says why).
  virtual std::optional<RunMode> mode() = 0;
  virtual std::string cannot_read_mode() const { return ""; }
  // How old a value read() returns may be: 0 for a link that asks the PLC at every read; the
  // longest gap measured between a node's messages for one that reads what a node published.
  virtual uint64_t max_age_us() const { return 0; }
};

}  // namespace scenario
}  // namespace plc_cell
