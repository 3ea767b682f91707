#include "request_guard.h"

#include <algorithm>
#include <cctype>

namespace plc_cell {
namespace monitor {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 5 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// 127.x.y.z: the whole loopback network.
bool loopback_v4(const std::string& h) {
  if (h.rfind("127.", 0) != 0) return false;
  int dots = 0;
  for (char c : h) {
    if (c == '.') ++dots;
    else if (!std::isdigit(static_cast<unsigned char>(c))) return false;
  }
  return dots == 3;
}

}  // namespace

std::string host_name(const std::string& header) {
  std::string h = lower(header);
  if (h.empty() || h.size() > 255) return "";
  if (h[0] == '[') {
    const auto close = h.find(']');
    if (close == std::string::npos) return "";
    const std::string rest = h.substr(close + 1);
    if (!rest.empty() && (rest[0] != ':' || !all_digits(rest.substr(1)))) return "";
    return h.substr(1, close - 1);
  }
  const auto colon = h.find(':');
  if (colon != std::string::npos) {
    if (!all_digits(h.substr(colon + 1))) return "";
    h = h.substr(0, colon);
  }
  const bool ok = !h.empty() && std::all_of(h.begin(), h.end(), [](unsigned char c) {
    return std::isalnum(c) || c == '.' || c == '-' || c == '_';
  });
  return ok ? h : "";
}

RequestGuard::RequestGuard(std::string bound_host, std::vector<std::string> allowed_hosts)
    : bound_(lower(std::move(bound_host))) {
  for (auto& h : allowed_hosts) allowed_.push_back(lower(h));
}

bool RequestGuard::host_allowed(const std::string& name) const {
  if (name == "localhost" || name == "::1" || loopback_v4(name)) return true;
  if (name == bound_ && bound_ != "0.0.0.0" && bound_ != "::") return true;
  return std::find(allowed_.begin(), allowed_.end(), name) != allowed_.end();
}

std::string RequestGuard::refusal(const std::string& host, const std::string& origin) const {
  const std::string name = host_name(host);
  if (name.empty()) return "Host header '" + host + "' is missing or malformed";
  if (!host_allowed(name))
    return "Host '" + host + "' is not this server (loopback, the bound address or allowed_hosts)";
  if (!origin.empty() && lower(origin) != "http://" + lower(host))
    return "Origin '" + origin + "' is not this server (http://" + host + "): cross-site requests are refused";
  return "";
}

}  // namespace monitor
}  // namespace plc_cell
