#include "plc_cell/temp/pwmda.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/temp/hspwm.h"

namespace plc_cell {
namespace temp {

double pwmda_voltage(double duty, bool trimmed) {
  return std::clamp(duty, 0.0, 1.0) * (trimmed ? 10.0 : kPwmdaFullScaleV);
}

std::vector<PwmdaDef> parse_pwmda_config(const YAML::Node& node, const std::string& file) {
  std::vector<PwmdaDef> defs;
  if (!node || node.IsNull()) return defs;
  YamlReader r(file);
  if (!node.IsSequence()) r.fail(node, "modules.pwmda", "expected a list of outputs");
  std::set<int> used;
  for (size_t i = 0; i < node.size(); ++i) {
    const YAML::Node n = node[i];
    const std::string k = "modules.pwmda[" + std::to_string(i) + "]";
    r.only(n, k, {"name", "output", "trim"});
    PwmdaDef d;
    if (n["name"]) d.name = r.str(n["name"], k + ".name");
    if (!n["output"]) r.fail(n, k, "missing 'output' (Y0, Y2, Y4 or Y6)");
    const std::string y = r.str(n["output"], k + ".output");
    static const char* kY[kHsPwmOutputs] = {"Y0", "Y2", "Y4", "Y6"};
    d.pw = -1;
    for (int p = 0; p < kHsPwmOutputs; ++p)
      if (y == kY[p]) d.pw = p;
    if (d.pw < 0) r.fail(n["output"], k + ".output", "a PWMDA fits a high-speed output: Y0, Y2, Y4 or Y6");
    if (!used.insert(d.pw).second) r.fail(n["output"], k + ".output", y + " has a PWMDA already");
    if (d.name.empty()) d.name = y;
    if (n["trim"]) {
      const std::string t = r.str(n["trim"], k + ".trim");
      if (t != "none" && t != "hardware") r.fail(n["trim"], k + ".trim", "expected none or hardware");
      d.trimmed = t == "hardware";
    }
    defs.push_back(d);
  }
  return defs;
}

PwmdaOutputs::PwmdaOutputs(std::vector<PwmdaDef> defs) : defs_(std::move(defs)), volts_(defs_.size(), 0.0) {}

void PwmdaOutputs::attached(ScanEngine& e) { engine_ = &e; }
void PwmdaOutputs::detached(ScanEngine&) { engine_ = nullptr; }

void PwmdaOutputs::before_inputs(uint64_t now_us) {
  const double dt = have_time_ && now_us > last_us_ ? (now_us - last_us_) * 1e-6 : 0.0;
  have_time_ = true;
  last_us_ = now_us;
  // First-order filter, exact for an input held over dt (any scan period, same curve).
  const double a = 1.0 - std::exp(-dt / kPwmdaTimeConstantS);
  for (size_t k = 0; k < defs_.size(); ++k) {
    const HsPwmChannel ch = engine_ ? hspwm_channel(*engine_, defs_[k].pw) : HsPwmChannel{};
    const double target = ch.running ? pwmda_voltage(ch.duty, defs_[k].trimmed) : 0.0;
    volts_[k] += (target - volts_[k]) * a;
  }
}

void PwmdaOutputs::on_stop() {
  if (engine_) hspwm_reset(*engine_);
}

std::unique_ptr<PwmdaOutputs> make_pwmda_outputs(const YAML::Node& document, const std::string& file) {
  const YAML::Node modules = document.IsMap() ? document["modules"] : YAML::Node();
  if (!modules || !modules.IsMap() || !modules["pwmda"]) return nullptr;
  return std::make_unique<PwmdaOutputs>(parse_pwmda_config(modules["pwmda"], file));
}

}  // namespace temp
}  // namespace plc_cell
