// The protocol server kinds a cell offers. A new kind is its servers, its ServerKind
// (settings schema and factory, next to the servers) and one line here; the YAML, plc_node
// and `plc_cell run` then take its settings with no other change.
#include "plc_cell/fatek/server_kind.h"
#include "plc_cell/modbus/server_kind.h"
#include "plc_cell/monitor/server_kind.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/tri/server_kind.h"

namespace plc_cell {

const std::vector<ServerKind>& Cell::server_kinds() {
  static const std::vector<ServerKind> kinds = {fatek::server_kind(), modbus::server_kind(), tri::server_kind(),
                                                monitor::server_kind()};
  return kinds;
}

}  // namespace plc_cell
