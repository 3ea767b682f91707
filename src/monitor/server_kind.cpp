#include "plc_cell/monitor/server_kind.h"

#include "plc_cell/config/cell_config.h"
#include "plc_cell/monitor/http_server.h"
#include "plc_cell/monitor/live_source.h"

namespace plc_cell {
namespace monitor {

ServerKind server_kind() {
  ServerKind k;
  k.name = "http";
  k.title = "browser monitor over HTTP and WebSocket (docs/monitor-api.md)";
  k.settings = {setting("tcp", SettingType::HostPort, "HOST:PORT the monitor page is served on (e.g. 127.0.0.1:8080)")};
  for (auto& s : client_limits(16)) k.settings.push_back(s);
  // A browser page can do what its user can: read-only unless ranges are given.
  k.settings[1].fallback = "none";
  k.settings[1].help = "what pages may write and force: none (default), all, or ranges such as D0-D99,M800";
  k.settings.push_back(setting("allowed_hosts", SettingType::Text,
                               "a Host name the pages may use besides loopback and the bound address; repeatable"));
  k.settings.back().repeatable = true;
  k.settings.push_back(setting("assets", SettingType::Text, "the page's folder (default: the package's share/monitor)"));
  k.settings.push_back(setting("edit", SettingType::Boolean,
                               "pages may change the running program (the Edit tab's Apply and Undo); needs "
                               "writable: all (docs/online-change.md)",
                               "false"));
  k.make = [](const ServerContext& c, const Settings& v) {
    std::vector<std::unique_ptr<Server>> out;
    if (v.text("tcp").empty()) return out;
    std::string name = "cell";
    if (c.config) name = "cell " + c.config->name;
    const HttpSettings s = http_settings(v);
    if (s.edit && !s.writable.everything())
      throw Error("servers.http.edit: true needs servers.http.writable: all (a page that may change the program "
                  "may change anything)");
    out.push_back(std::make_unique<HttpServer>(std::make_unique<LiveSource>(c, name), s));
    return out;
  };
  return k;
}

}  // namespace monitor
}  // namespace plc_cell
