#include "cell_options.h"

#include <algorithm>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace cli {
namespace {

std::string name_of(const std::string& option) { return option.substr(2); }  // "--modbus-id" -> "modbus-id"

// A value the cell would refuse is the user's typing: status 2 with the usage.
SettingOverride checked(const SettingSpec& spec, SettingOverride o) {
  for (const auto& v : o.values) {
    try {
      check_setting(spec, v);
    } catch (const Error& e) {
      throw UsageError(o.origin + " " + v + ": " + e.what());
    }
  }
  if (o.values.size() > 1 && !spec.repeatable) throw UsageError(o.origin + " given more than once");
  return o;
}

}  // namespace

std::vector<std::string> server_options() {
  std::vector<std::string> out;
  for (const auto& k : Cell::server_kinds())
    for (const auto& s : k.settings) {
      out.push_back(name_of(k.option(s)));
      if (!s.cli_alias.empty()) out.push_back(s.cli_alias);
    }
  return out;
}

CellOverrides cell_overrides(const Args& args) {
  CellOverrides o;
  o.program = args.get("program");
  const std::pair<const char*, const char*> run[] = {
      {"scan", "scan_period"}, {"rt-priority", "rt_priority"}, {"persist", "persist_file"},
      {"persist-interval", "persist_interval"}, {"engine", "engine"}, {"rtc-start", "rtc_start"}};
  for (const auto& r : run) {
    if (!args.has(r.first)) continue;
    const auto& specs = Cell::run_settings();
    const auto s = std::find_if(specs.begin(), specs.end(), [&](const SettingSpec& x) { return x.key == r.second; });
    std::vector<std::string> values = args.all(r.first);
    // A whole number is read as the tool reads every count (0x.. too), with its message.
    if (s->type == SettingType::Integer) values = {std::to_string(args.get_int(r.first, 0, s->lo, s->hi))};
    o.run.push_back(checked(*s, {"", r.second, values, std::string("--") + r.first}));
  }
  for (const auto& k : Cell::server_kinds())
    for (const auto& s : k.settings)
      for (const std::string& name : {name_of(k.option(s)), s.cli_alias}) {
        if (name.empty() || !args.has(name)) continue;
        o.servers.push_back(checked(s, {k.name, s.key, args.all(name), "--" + name}));
      }
  return o;
}

}  // namespace cli
}  // namespace plc_cell
