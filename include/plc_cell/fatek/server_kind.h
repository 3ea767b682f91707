#pragma once
// The FATEK slave as a server kind: servers.fatek in the cell YAML, ~fatek_* on plc_node,
// --fatek-* on `plc_cell run` (docs/fatek.md).
#include "plc_cell/config/server_kind.h"

namespace plc_cell {
namespace fatek {

ServerKind server_kind();

}  // namespace fatek
}  // namespace plc_cell
