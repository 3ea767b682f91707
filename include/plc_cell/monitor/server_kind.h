#pragma once
// The `http` server kind: the browser monitor of the cell (docs/monitor-api.md), offered
// as servers.http in the cell YAML, --http-* by `plc_cell run`, ~http_* by plc_node.
#include "plc_cell/config/server_kind.h"

namespace plc_cell {
namespace monitor {

ServerKind server_kind();

}  // namespace monitor
}  // namespace plc_cell
