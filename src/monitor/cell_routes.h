#pragma once
// Which cell a request is for (docs/monitor-api.md, "A line's cells"): /cell/NAME/... is cell
// NAME's, its rest the target its Api sees, so a cell's page and API under /cell/NAME/ are
// the lone cell's ones under /. Without /cell/, a lone cell's set (SourceSet::alone) is its
// cell; any other set is its overview (overview.h).
#include <memory>
#include <string>
#include <vector>

#include "api.h"

namespace plc_cell {
namespace monitor {

struct Route {
  Api* api = nullptr;      // the cell's Api; nullptr: the overview's request, or error
  std::string target;      // the target as the cell's Api takes it
  bool overview = false;   // the overview's page or API
  std::string error;       // 404's reason ("" = routed)
};

Route route(const std::string& target, const SourceSet& set, const std::vector<std::unique_ptr<Api>>& apis);

}  // namespace monitor
}  // namespace plc_cell
