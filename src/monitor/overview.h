#pragma once
// The overview of the cells one monitor serves (docs/monitor.md, "One monitor for a
// line"): each cell's RUN/STOP, scan figures, faults and forced points as its own status
// gives them, and each wire's two ends as read now. GET /api/overview and, for a set of
// several cells, the page at / and GET /api/session.
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "api.h"

namespace plc_cell {
namespace monitor {

class Overview {
 public:
  Overview(const SourceSet& set, const std::vector<std::unique_ptr<Api>>& apis, const HttpSettings& settings)
      : set_(set), apis_(apis), settings_(settings) {}
  // GET path of the overview (cell_routes.h decided it is one).
  ApiReply get(const std::string& path) const;
  nlohmann::json json() const;

 private:
  nlohmann::json cell_json(size_t i) const;
  nlohmann::json wire_json(const SetWire& w) const;
  const SourceSet& set_;
  const std::vector<std::unique_ptr<Api>>& apis_;
  const HttpSettings& settings_;
};

}  // namespace monitor
}  // namespace plc_cell
