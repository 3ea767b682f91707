// The forms of --target, one entry each: a new protocol's target is its LinkedPlc and a line here.
#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/hardware/modbus_plc.h"
#include "plc_cell/hardware/remote_plc.h"
#include "plc_cell/hardware/target_spec.h"
#include "plc_cell/io/endpoint.h"

namespace plc_cell {
namespace hardware {

namespace {

// The TCP forms take HOST:PORT, the serial forms a device path.
std::string tcp_endpoint(const std::string& form, const std::string& text) {
  const Endpoint e = parse_endpoint(text);
  if (e.serial) throw Error(form + ": '" + text + "' is a serial device: use the -serial form of this protocol");
  return text;
}
std::string serial_endpoint(const std::string& form, const std::string& text) {
  if (text.empty() || text[0] != '/')
    throw Error(form + ": '" + text + "' is not a device path (/dev/ttyUSB0, /dev/ttyUSB0:9600:7E1)");
  return text;
}

}  // namespace

const std::vector<TargetKind>& target_kinds() {
  static const std::vector<TargetKind> kinds = {
      {"fatek://", "fatek://HOST:PORT", "station", 1, 1, 254,
       [](const std::string& e, int unit, const TargetOptions& o) {
         return open_fatek(tcp_endpoint("fatek://", e), unit, o.timeout_ms, o.retries);
       }},
      {"fatek-serial:", "fatek-serial:DEVICE[:BAUD[:FORMAT]]", "station", 1, 1, 254,
       [](const std::string& e, int unit, const TargetOptions& o) {
         return open_fatek(serial_endpoint("fatek-serial:", e), unit, o.timeout_ms, o.retries);
       }},
      {"tri://", "tri://HOST:PORT", "id", 1, 0, 255,
       [](const std::string& e, int unit, const TargetOptions& o) {
         return open_tri(tcp_endpoint("tri://", e), unit, o.timeout_ms, o.retries);
       }},
      {"tri-serial:", "tri-serial:DEVICE[:BAUD[:FORMAT]]", "id", 1, 0, 255,
       [](const std::string& e, int unit, const TargetOptions& o) {
         return open_tri(serial_endpoint("tri-serial:", e), unit, o.timeout_ms, o.retries);
       }},
      {"modbus://", "modbus://HOST:PORT", "id", 1, 1, 247,
       [](const std::string& e, int unit, const TargetOptions& o) -> std::unique_ptr<scenario::LinkedPlc> {
         return std::make_unique<ModbusPlc>(tcp_endpoint("modbus://", e), false, unit, o.timeout_ms, o.retries);
       }},
      {"modbus-rtu:", "modbus-rtu:DEVICE[:BAUD[:FORMAT]]", "id", 1, 1, 247,
       [](const std::string& e, int unit, const TargetOptions& o) -> std::unique_ptr<scenario::LinkedPlc> {
         return std::make_unique<ModbusPlc>(serial_endpoint("modbus-rtu:", e), true, unit, o.timeout_ms, o.retries);
       }},
  };
  return kinds;
}

std::unique_ptr<scenario::LinkedPlc> open_target(const TargetOptions& o) {
  const auto& kinds = target_kinds();
  const auto kind = std::find_if(kinds.begin(), kinds.end(), [&](const TargetKind& k) {
    return o.text.compare(0, k.prefix.size(), k.prefix) == 0;
  });
  if (kind == kinds.end()) {
    std::string forms;
    for (const auto& k : kinds) forms += (forms.empty() ? "" : ", ") + k.form;
    throw Error("--target " + o.text + ": expected one of " + forms);
  }
  const bool station = kind->unit_option == "station";
  if ((station && o.id) || (!station && o.station))
    throw Error(std::string(station ? "--id" : "--station") + " does not go with " + kind->prefix + " (it takes --" +
                kind->unit_option + ")");
  const int unit = (station ? o.station : o.id).value_or(kind->default_unit);
  if (unit < kind->min_unit || unit > kind->max_unit)
    throw Error("--" + kind->unit_option + " " + std::to_string(unit) + ": out of range " +
                std::to_string(kind->min_unit) + ".." + std::to_string(kind->max_unit) + " for " + kind->prefix);
  return kind->open(o.text.substr(kind->prefix.size()), unit, o);
}

}  // namespace hardware
}  // namespace plc_cell
