// The scenario file's `hardware:` key: whether, and on which targets, its cases may run on a
// real PLC (docs/testing-on-hardware.md, "Safety").
#include <fnmatch.h>

#include "sections.h"

namespace plc_cell {
namespace scenario {

namespace {

std::vector<std::string> target_patterns(const YamlReader& r, const YAML::Node& list, const std::string& key) {
  if (!list.IsSequence() || list.size() == 0)
    r.fail(list, key, "expected a list of targets, e.g. [fatek://192.168.1.5:500, tri-serial:/dev/ttyUSB0]");
  std::vector<std::string> out;
  for (size_t i = 0; i < list.size(); ++i) {
    const std::string t = r.str(list[i], key + "[" + std::to_string(i) + "]");
    if (t.empty()) r.fail(list[i], key, "an empty target");
    out.push_back(t);
  }
  return out;
}

}  // namespace

std::string HardwarePermission::refuses(const std::string& target) const {
  if (!line) return "this file does not say that it may run on a PLC: add 'hardware: true' (or a list of the "
                    "targets it may run on) once its cases drive everything the cell's simulation played";
  if (!allowed) return "this file says 'hardware: false': it runs in virtual time only";
  if (targets.empty()) return "";
  for (const auto& t : targets)
    if (::fnmatch(t.c_str(), target.c_str(), 0) == 0) return "";
  std::string list;
  for (const auto& t : targets) list += (list.empty() ? "" : ", ") + t;
  return "this file allows only the targets " + list + ", not " + target;
}

HardwarePermission read_hardware(const YamlReader& r, const YAML::Node& n, ErrorList& errors) {
  HardwarePermission h;
  if (!n) return h;
  h.line = YamlReader::line(n);
  errors.collect([&] {
    if (n.IsScalar()) {
      h.allowed = r.boolean(n, "hardware");
    } else if (n.IsSequence()) {
      h.allowed = true;
      h.targets = target_patterns(r, n, "hardware");
    } else {
      r.only(n, "hardware", {"targets", "require_run"});
      h.allowed = true;
      if (n["targets"] && !(n["targets"].IsScalar() && n["targets"].Scalar() == "any"))
        h.targets = target_patterns(r, n["targets"], "hardware.targets");
      if (n["require_run"]) h.require_run = r.boolean(n["require_run"], "hardware.require_run");
    }
  }, r.file(), n);
  return h;
}

}  // namespace scenario
}  // namespace plc_cell
