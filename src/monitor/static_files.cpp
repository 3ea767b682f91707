#include "static_files.h"

#include <sys/stat.h>

#include "json_views.h"
#include "plc_cell/core/file_text.h"

namespace plc_cell {
namespace monitor {
namespace {

std::string content_type(const std::string& path) {
  static const std::pair<const char*, const char*> types[] = {
      {".html", "text/html; charset=utf-8"}, {".js", "text/javascript; charset=utf-8"},
      {".mjs", "text/javascript; charset=utf-8"}, {".css", "text/css; charset=utf-8"},
      {".json", "application/json"}, {".svg", "image/svg+xml"}, {".png", "image/png"},
      {".ico", "image/x-icon"}, {".map", "application/json"}, {".txt", "text/plain; charset=utf-8"}};
  for (const auto& [ext, type] : types) {
    const std::string e = ext;
    if (path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0) return type;
  }
  return "application/octet-stream";
}

// Segments of plain names only: no "..", ".", empty segment, backslash, NUL or escapes.
std::string unsafe_part(const std::string& rel) {
  if (rel.empty()) return "an empty file name";
  if (rel.find_first_of(std::string("\\%\0", 3)) != std::string::npos) return "a backslash, '%' or NUL";
  size_t start = 0;
  while (start <= rel.size()) {
    size_t end = rel.find('/', start);
    if (end == std::string::npos) end = rel.size();
    const std::string seg = rel.substr(start, end - start);
    if (seg.empty() || seg == "." || seg == "..") return "the segment '" + seg + "'";
    start = end + 1;
  }
  return "";
}

StaticReply error(int status, const std::string& why) { return {status, "application/json", error_body(why)}; }

StaticReply serve(const std::string& root, const std::string& rel, const std::string& shown) {
  if (const std::string bad = unsafe_part(rel); !bad.empty()) return error(400, shown + ": refused, it holds " + bad);
  const std::string file = root + "/" + rel;
  struct stat st {};
  if (root.empty() || ::stat(file.c_str(), &st) != 0 || !S_ISREG(st.st_mode))
    return error(404, shown + ": no such file");
  if (size_t(st.st_size) > kMaxStaticFile) return error(404, shown + ": too large to serve");
  std::optional<std::string> text = file_text(file);
  if (!text) return error(404, shown + ": cannot be read");
  return {200, content_type(file), std::move(*text)};
}

}  // namespace

StaticReply static_file(const std::string& path, const std::string& asset_root, const std::string& vendor_root) {
  if (path == "/" || path == "/index.html") return serve(asset_root, "index.html", path);
  if (path.rfind("/assets/", 0) == 0) return serve(asset_root, path.substr(8), path);
  if (path.rfind("/vendor/", 0) == 0) return serve(vendor_root, path.substr(8), path);
  return error(404, path + ": no such page (/, /assets/..., /vendor/..., /api/...)");
}

}  // namespace monitor
}  // namespace plc_cell
