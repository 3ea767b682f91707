#pragma once
// ~read, ~write, ~force and ~release (and ~read_forced where the node reads which points are
// forced from the PLC): the same names, types, checks and replies on every
// node that fronts a PLC (plc_node over its own cell, fatek_bridge over a FATEK link), so a
// robot stack switches between the simulated cell and the real one by a launch argument.
// The node says what its PLC can do (MemoryAccess); the handlers resolve names, check and
// encode the request, and turn every failure into a reply with a message.
#include <cstdint>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "plc_cell/core/address.h"

namespace plc_cell {

class MemoryAccess {
 public:
  virtual ~MemoryAccess() = default;
  // A signal name of the node's YAML, or an address (X3, R100, DR4088).
  virtual Address resolve(const std::string& text) const = 0;
  virtual std::vector<uint32_t> read(const Address& start, uint32_t count) = 0;
  // Raw elements (encode_element's bit patterns): all of them, or nothing and an exception.
  virtual void write(const Address& start, const std::vector<uint32_t>& raw) = 0;
  // Locks a discrete at value (FATEK's DISABLE, then set or reset).
  virtual void force(const Address& bit, bool value) = 0;
  // Frees bit, or every forced discrete when bit is null; returns those that were forced.
  virtual std::vector<Address> release(const Address* bit) = 0;
  // Whether the node reads from the PLC which discretes are forced (then ~read_forced is
  // offered), and which of bits are. plc_node publishes ~forced instead.
  virtual bool reads_forced() const { return false; }
  virtual std::vector<bool> forced(const std::vector<Address>& bits);
};

// Advertises the services on pnh; access must outlive the returned servers.
std::vector<ros::ServiceServer> advertise_memory_services(ros::NodeHandle& pnh, MemoryAccess& access);

}  // namespace plc_cell
