#pragma once
// The page's files: GET / and /assets/... from the asset root, /vendor/<lib>/... from the
// Debian JavaScript libraries. A path that could leave its folder is refused, not cleaned.
#include <string>

namespace plc_cell {
namespace monitor {

struct StaticReply {
  int status = 200;
  std::string type;  // content type
  std::string body;  // the file, or the JSON error
};

constexpr size_t kMaxStaticFile = 16u << 20;

// nullptr-free: target is the request path without the query.
StaticReply static_file(const std::string& path, const std::string& asset_root, const std::string& vendor_root);

}  // namespace monitor
}  // namespace plc_cell
