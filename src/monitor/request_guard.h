#pragma once
// Who may talk to the monitor: a browser page of this server only. The Host header must
// name a loopback address, the bound address or an allowed host (a DNS-rebinding page's
// request carries its own name), and an Origin header, when present, must be this very
// server (a foreign page's request carries its origin). docs/monitor-api.md, "Security".
#include <string>
#include <vector>

namespace plc_cell {
namespace monitor {

class RequestGuard {
 public:
  RequestGuard(std::string bound_host, std::vector<std::string> allowed_hosts);
  // "" when the request may go on, else why it may not.
  std::string refusal(const std::string& host, const std::string& origin) const;

 private:
  bool host_allowed(const std::string& name) const;
  std::string bound_;
  std::vector<std::string> allowed_;
};

// "Host:port" / "[v6]:port" without the port, lower case; "" when malformed.
std::string host_name(const std::string& host_header);

}  // namespace monitor
}  // namespace plc_cell
