#pragma once
// The TRi host-link slave as a server kind: servers.tri in the cell YAML, ~tri_* on
// plc_node, --tri-* on `plc_cell run` (docs/tri.md).
#include "plc_cell/config/server_kind.h"

namespace plc_cell {
namespace tri {

ServerKind server_kind();

}  // namespace tri
}  // namespace plc_cell
