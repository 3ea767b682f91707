#include "cell_options.h"

#include <algorithm>
#include <iomanip>
#include <sstream>

#include "plc_cell/sim/virtual_run.h"

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

// One --set ADDR=VALUE, written before the first scan.
void apply_set(Cell& cell, const std::string& s, const std::string& shown) {
  const auto eq = s.find('=');
  if (eq == std::string::npos) throw UsageError("--set takes ADDR=VALUE, got '" + shown + "'");
  const Address a = cell.config().resolve(s.substr(0, eq));
  int64_t v;
  try {
    size_t used = 0;
    v = std::stoll(s.substr(eq + 1), &used, 0);
    if (used != s.size() - eq - 1) throw std::invalid_argument("x");
  } catch (const std::exception&) {
    throw UsageError("--set " + shown + ": value is not a number");
  }
  // A negative value is the two's complement of the register's width (R1=-500).
  const int bits = value_bits(a);
  if (v < 0 && bits > 1 && v >= -(int64_t(1) << (bits - 1))) v &= bits == 16 ? 0xFFFF : 0xFFFFFFFFLL;
  if (v < 0) throw UsageError("--set " + shown + ": value below the address's range");
  cell.plc().write(a, {static_cast<uint32_t>(v)});
}

std::string seconds(uint64_t us) {
  std::ostringstream s;
  s << us / 1000000 << "." << std::setw(6) << std::setfill('0') << us % 1000000;
  return s.str();
}

}  // namespace cli
}  // namespace plc_cell
