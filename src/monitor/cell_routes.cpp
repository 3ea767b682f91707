#include "cell_routes.h"

namespace plc_cell {
namespace monitor {

Route route(const std::string& target, const SourceSet& set, const std::vector<std::unique_ptr<Api>>& apis) {
  Route r;
  static const std::string kCell = "/cell/";
  if (target.rfind(kCell, 0) == 0) {
    const size_t end = target.find_first_of("/?", kCell.size());
    const std::string name = target.substr(kCell.size(), end == std::string::npos ? std::string::npos : end - kCell.size());
    const int i = set.find(name);
    if (i < 0) {
      r.error = "no cell '" + name.substr(0, 64) + "' in this monitor (cells: " + set.names() + ")";
      return r;
    }
    r.api = apis[size_t(i)].get();
    r.target = end == std::string::npos ? "/" : target.substr(end);
    if (r.target[0] == '?') r.target = "/" + r.target;
    return r;
  }
  const std::string path = target.substr(0, target.find('?'));
  const bool page = path == "/" || path == "/index.html";
  if (path == "/api/overview" || (!set.alone() && (page || path == "/api/session"))) {
    r.overview = true;
    r.target = target;
    return r;
  }
  if (!set.alone() && path.rfind("/api/", 0) == 0) {
    r.error = path + ": this monitor serves " + std::to_string(set.size()) + " cells (" + set.names() +
              "): a cell's API is /cell/NAME" + path;
    return r;
  }
  // A lone cell's page and API, and every cell's page files (/assets/, /vendor/).
  r.api = apis.front().get();
  r.target = target;
  return r;
}

}  // namespace monitor
}  // namespace plc_cell
