#include "plc_cell/ros/server_params.h"

#include <iomanip>
#include <sstream>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace {

// A parameter as the text a YAML file or an option would give: numbers in the same units
// (durations in seconds), lists for repeatable settings.
std::vector<std::string> texts(const XmlRpc::XmlRpcValue& v, const std::string& name) {
  std::ostringstream s;
  switch (v.getType()) {
    case XmlRpc::XmlRpcValue::TypeString:
      return {static_cast<std::string>(const_cast<XmlRpc::XmlRpcValue&>(v))};
    case XmlRpc::XmlRpcValue::TypeBoolean:
      return {static_cast<bool>(const_cast<XmlRpc::XmlRpcValue&>(v)) ? "true" : "false"};
    case XmlRpc::XmlRpcValue::TypeInt:
      return {std::to_string(static_cast<int>(const_cast<XmlRpc::XmlRpcValue&>(v)))};
    case XmlRpc::XmlRpcValue::TypeDouble:
      s << std::setprecision(12) << static_cast<double>(const_cast<XmlRpc::XmlRpcValue&>(v));
      return {s.str()};
    case XmlRpc::XmlRpcValue::TypeArray: {
      std::vector<std::string> out;
      for (int i = 0; i < v.size(); ++i)
        for (const auto& t : texts(const_cast<XmlRpc::XmlRpcValue&>(v)[i], name)) out.push_back(t);
      return out;
    }
    default:
      throw Error(name + ": expected a string or a number");
  }
}

}  // namespace

CellOverrides cell_overrides(const ros::NodeHandle& pnh) {
  CellOverrides o;
  pnh.param<std::string>("program", o.program, "");
  // A cell in virtual time reads nothing of the host's clock (its RTC starts at a fixed instant).
  pnh.param("virtual_time", o.virtual_time, false);
  XmlRpc::XmlRpcValue v;
  for (const auto& spec : Cell::run_settings())
    if (pnh.getParam(spec.key, v)) o.run.push_back({"", spec.key, texts(v, "~" + spec.key), "~" + spec.key});
  for (const auto& k : Cell::server_kinds())
    for (const auto& s : k.settings) {
      // Silently ignoring an old name would run the server at the default instead.
      if (!s.retired_ros.empty() && pnh.hasParam(s.retired_ros))
        throw Error("~" + s.retired_ros + " is no longer read: give " + k.parameter(s) +
                    (s.type == SettingType::Duration ? " in seconds" : ""));
      const std::string name = k.parameter(s);
      if (pnh.getParam(name.substr(1), v)) o.servers.push_back({k.name, s.key, texts(v, name), name});
    }
  return o;
}

}  // namespace plc_cell
