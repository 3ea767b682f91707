#pragma once
// The PLC a `plc_cell test --target` runs on, as its text says it (docs/testing-on-hardware.md):
// fatek://HOST:PORT, fatek-serial:DEVICE[:BAUD[:FORMAT]], tri://HOST:PORT,
// tri-serial:DEVICE[...], modbus://HOST:PORT, modbus-rtu:DEVICE[...]. Each form is a
// TargetKind of target_kinds(): a new protocol is one more entry there and its LinkedPlc.
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/scenario/linked_plc.h"

namespace plc_cell {
namespace hardware {

struct TargetOptions {
  std::string text;            // --target, as given
  std::optional<int> station;  // --station (FATEK)
  std::optional<int> id;       // --id (TRi device ID, Modbus unit id)
  int timeout_ms = 1000;       // --timeout: one transaction
  int retries = 1;             // --retries: after a time-out or a garbled answer
};

struct TargetKind {
  std::string prefix;      // "fatek://"
  std::string form;        // "fatek://HOST:PORT"
  std::string unit_option;  // "station" or "id"
  int default_unit = 1;
  int min_unit = 1, max_unit = 254;
  // The link, not connected yet: its first transaction connects. Throws Error for an
  // endpoint that does not parse (or a serial device that does not exist).
  std::function<std::unique_ptr<scenario::LinkedPlc>(const std::string& endpoint, int unit, const TargetOptions&)> open;
};

const std::vector<TargetKind>& target_kinds();

// The PLC of o.text, not connected. Throws Error: an unknown form (listing the forms), a
// bad endpoint, the other protocol's option (--station on a TRi), a unit out of range.
std::unique_ptr<scenario::LinkedPlc> open_target(const TargetOptions& o);

}  // namespace hardware
}  // namespace plc_cell
