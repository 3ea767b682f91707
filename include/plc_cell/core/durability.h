#pragma once
// Where "a client was told its write succeeded" meets persistence. The Plc calls
// capture() under its lock after a client write, then wait() without the lock before
// the caller replies: so an acknowledged write is never lost (docs/reliability.md).
// Core only knows this interface; src/persist/ implements it.
#include <cstdint>

namespace plc_cell {

class Memory;
class ScanEngine;

class Durability {
 public:
  virtual ~Durability() = default;
  // Under the Plc lock: record the current state; returns a ticket for wait().
  virtual uint64_t capture(const ScanEngine& e, const Memory& m) = 0;
  // Without the lock: returns once the state of that ticket is as durable as configured.
  virtual void wait(uint64_t ticket) = 0;
};

}  // namespace plc_cell
