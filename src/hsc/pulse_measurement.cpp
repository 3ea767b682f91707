#include "plc_cell/hsc/pulse_measurement.h"

#include <algorithm>
#include <cctype>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/hsc/hsc_config.h"

namespace plc_cell {
namespace hsc {

bool PulseMeasurementConfig::measured(int x) const {
  return std::find(inputs.begin(), inputs.end(), x) != inputs.end();
}

namespace {

int input_pin(const YamlReader& r, const YAML::Node& n, const std::string& key) {
  std::string s = r.str(n, key);
  for (auto& c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (s.size() < 2 || s.size() > 3 || s[0] != 'X' || !std::all_of(s.begin() + 1, s.end(), ::isdigit))
    r.fail(n, key, "'" + r.str(n, key) + "' is not an input X0-X15");
  const int x = std::stoi(s.substr(1));
  if (x > 15) r.fail(n, key, "'" + s + "': only X0-X15 are high-speed inputs");
  return x;
}

// The counter x is a counting input of (a timer counts no input), or -1.
int counter_of(const std::array<CounterDef, 8>& counters, int x) {
  for (int n = 0; n < 8; ++n) {
    const CounterDef& d = counters[n];
    if (d.used && !d.timer && (d.pin_a == x || d.pin_b == x)) return n;
  }
  return -1;
}

}  // namespace

PulseMeasurementConfig parse_pulse_measurement(const YAML::Node& node, const std::string& file,
                                               const std::array<CounterDef, 8>& counters) {
  PulseMeasurementConfig cfg;
  if (!node || node.IsNull()) return cfg;
  const std::string key = "counters.pulse_measurement";
  YamlReader r(file);
  if (!node.IsMap()) r.fail(node, key, "expected a mapping such as {inputs: [X0], unit: us}");
  r.only(node, key, {"inputs", "unit", "timeout"});
  const YAML::Node l = node["inputs"];
  if (!l) r.fail(node, key, "needs inputs: the counting inputs to measure, e.g. [X0]");
  if (!l.IsSequence() || l.size() == 0) r.fail(l, key + ".inputs", "expected a list of counting inputs such as [X0, X4]");
  for (const auto& e : l) {
    const int x = input_pin(r, e, key + ".inputs");
    if (cfg.measured(x)) r.fail(e, key + ".inputs", "X" + std::to_string(x) + " is listed twice");
    const int n = counter_of(counters, x);
    if (n < 0)
      r.fail(e, key + ".inputs", "X" + std::to_string(x) +
                                     " is not a counting input of a configured counter; pulse measurement "
                                     "works on a counter's counting input (hscN.a or hscN.b)");
    cfg.inputs.push_back(x);
    cfg.counter_of.push_back(n);
  }
  if (node["unit"]) {
    const std::string u = r.str(node["unit"], key + ".unit");
    if (u == "0.1us") cfg.tenths = true;
    else if (u != "us") r.fail(node["unit"], key + ".unit", "'" + u + "': expected us or 0.1us");
  }
  if (node["timeout"] && r.str(node["timeout"], key + ".timeout") != "auto") {
    cfg.timeout_ns = r.duration_us(node["timeout"], key + ".timeout") * 1000;
    if (cfg.timeout_ns == 0) r.fail(node["timeout"], key + ".timeout", "expected auto or a time of at least 1us, e.g. 500ms");
  }
  return cfg;
}

}  // namespace hsc
}  // namespace plc_cell
