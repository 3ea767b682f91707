// The cell YAML's axes: section.
#include "plc_cell/motion/axis_config.h"

#include <climits>
#include <map>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/error.h"
#include "plc_cell/motion/lin_table.h"

namespace plc_cell {
namespace motion {

namespace {
constexpr double kAnyNumber = 1e300;

// Analytic (edge-exact) signals can only drive the high-speed inputs.
int high_speed_input(const YamlReader& r, const YAML::Node& v, const std::string& what) {
  Address ad;
  std::string why;
  if (!try_parse_address(r.str(v, what), &ad, &why) || ad.area != Area::X ||
      ad.width != Width::Bit || ad.index > 15)
    r.fail(v, what, "expected a high-speed input X0-X15");
  return static_cast<int>(ad.index);
}

// The `at:` register of a table or parameter image.
Address register_at(const YamlReader& r, const YAML::Node& v, const std::string& key) {
  Address at;
  std::string why;
  if (!v["at"] || !try_parse_address(r.str(v["at"], key + ".at"), &at, &why) ||
      (at.area != Area::R && at.area != Area::D) || at.width != Width::Word)
    r.fail(v, key + ".at", "expected a register R or D");
  return at;
}

// A table's `at:` register and its `text:` parsed by parse (FUN140 or FUN147 form);
// a text error names its YAML line.
template <typename T, typename Parse>
Address table_text(const YamlReader& r, const YAML::Node& v, const std::string& key, Parse parse, T* out) {
  const Address at = register_at(r, v, key);
  if (!v["text"]) r.fail(v, key, "needs text (the manual's text form)");
  TableError e;
  if (!parse(r.str(v["text"], key + ".text"), out, &e)) {
    const YAML::Mark m = v["text"].Mark();
    // A block scalar starts on the line after its key.
    throw SourceError::at(r.file(), m.line + 1 + (e.line > 0 ? e.line : 0), 1,
                          "key '" + key + ".text': error " + std::to_string(e.code) + ": " + e.message);
  }
  return at;
}

using Given = std::map<std::string, YAML::Node>;  // output: and params: p-keys, for the clashes with stepspeed:

// axes.gpN: {table: {at:, text:}}, a FUN147 group's table.
void parse_group(const YamlReader& r, const std::string& key, const YAML::Node& v, GroupDef* g) {
  for (const auto& f : v) {
    if (f.first.as<std::string>() != "table") r.fail(f.first, "axes." + key, "expected table");
    g->table_at = table_text(r, f.second, "axes." + key + ".table", parse_lin_table, &g->table);
    g->has_table = true;
  }
}

void parse_output(const YamlReader& r, const YAML::Node& v, const std::string& key, AxisDef* a) {
  const std::string m = r.str(v, key);
  if (m == "UD") a->mode = OutputMode::UD;
  else if (m == "PR") a->mode = OutputMode::PR;
  else if (m == "AB") a->mode = OutputMode::AB;
  else r.fail(v, key, "expected UD, PR or AB");
  a->has_output = true;
}

void parse_wiring(const YamlReader& r, const YAML::Node& v, const std::string& key, int n, AxisDef* a) {
  if (!v.IsMap()) r.fail(v, key, "expected a map like {Y0: X0, Y1: X1}");
  a->wiring_line = v.Mark().line + 1;
  for (const auto& w : v) {
    const std::string y = w.first.as<std::string>();
    Address ya;
    std::string why;
    const int first = 2 * n;
    if (!try_parse_address(y, &ya, &why) || ya.area != Area::Y || ya.width != Width::Bit ||
        (int(ya.index) != first && int(ya.index) != first + 1))
      r.fail(w.first, key + "." + y, "expected this axis's pins Y" + std::to_string(first) +
                              " or Y" + std::to_string(first + 1));
    a->wired[ya.index - first] = high_speed_input(r, w.second, key + "." + y);
  }
}

void parse_encoder(const YamlReader& r, const YAML::Node& v, const std::string& key, EncoderDef* enc) {
  if (!v.IsMap() || !v["a"]) r.fail(v, key, "expected {a: Xn, b: Xm, periods_per_pulse: k}");
  enc->used = true;
  enc->line = v.Mark().line + 1;
  for (const auto& e : v) {
    const std::string ek = e.first.as<std::string>();
    if (ek == "a") enc->a = high_speed_input(r, e.second, key + ".a");
    else if (ek == "b") enc->b = high_speed_input(r, e.second, key + ".b");
    else if (ek == "periods_per_pulse") {
      enc->periods = r.integer(e.second, key + "." + ek, INT64_MIN, INT64_MAX);
      if (enc->periods < 1 || enc->periods > 1000) r.fail(e.second, key + "." + ek, "expected a whole number 1-1000");
    } else {
      r.fail(e.first, key + "." + ek, "unknown (a, b, periods_per_pulse)");
    }
  }
}

void parse_switches(const YamlReader& r, const YAML::Node& v, const std::string& pre, AxisDef* a) {
  if (!v.IsSequence()) r.fail(v, pre + "switches", "expected a list");
  for (const auto& s : v) {
    SwitchDef d;
    if (!s["x"]) r.fail(s, pre + "switches", "each switch needs x");
    Address ad;
    std::string why;
    if (!try_parse_address(r.str(s["x"], pre + "switches.x"), &ad, &why) || ad.area != Area::X ||
        ad.width != Width::Bit)
      r.fail(s["x"], pre + "switches.x", "expected an input X0-X255");
    d.x = static_cast<int>(ad.index);
    for (const auto& sf : s) {
      const std::string sk = sf.first.as<std::string>();
      if (sk == "x") continue;
      const int64_t val = r.integer(sf.second, pre + "switches." + sk, INT64_MIN, INT64_MAX);
      if (sk == "from") d.from = val;
      else if (sk == "to") d.to = val;
      else if (sk == "period") d.period = val;
      else if (sk == "offset") d.offset = val;
      else if (sk == "width") d.width = val;
      else r.fail(sf.first, pre + "switches." + sk, "unknown (x, from, to, period, offset, width)");
    }
    if (d.period < 0 || (d.period > 0 && (d.width < 1 || d.width >= d.period)))
      r.fail(s, pre + "switches", "period > width >= 1");
    if (d.from > d.to) r.fail(s, pre + "switches", "from must be <= to");
    a->switches.push_back(d);
  }
}

void parse_params(const YamlReader& r, const YAML::Node& v, const std::string& pre, AxisDef* a, Given* given) {
  a->has_params = true;
  if (!v.IsMap()) r.fail(v, pre + "params", "expected a mapping {p8: 100, ...} (at: a register for MPARA, optional)");
  a->params_image = bool(v["at"]);
  if (a->params_image) a->params_at = register_at(r, v, pre + "params");
  for (const auto& pf : v) {
    const std::string pk = pf.first.as<std::string>();
    if (pk == "at") continue;
    const int64_t val = r.integer(pf.second, pre + "params." + pk, INT64_MIN, INT64_MAX);
    const int n = pk[0] == 'p' ? param_number(pk) : -1;  // the YAML's keys are lower case
    if (!a->params.set(n, val)) r.fail(pf.first, pre + "params." + pk, "expected at, p0 ... p17");
    given->emplace(pk, pf.first);
  }
  ParamError pe;
  const int code = a->params.validate(&pe);
  if (code) r.fail(v, pre + "params", "parameter error " + std::to_string(code) + ": " + pe.message);
}

void check_stepspeed(const YamlReader& r, const std::string& pre, const AxisDef& a, const Given& given) {
  if (!a.stepspeed.used) return;
  // One ramp per axis: the step form replaces these FUN141 values, so giving both
  // would leave one silently unused.
  for (const char* pk : {"p4", "p5", "p8", "p12"})
    if (given.count(pk))
      r.fail(given.at(pk), pre + "params." + pk,
             "conflicts with stepspeed (its pps and accel_steps set the speeds and the ramp)");
  // The direction pin of the step form needs a pulse/direction output.
  if (a.has_output && a.mode != OutputMode::PR)
    r.fail(given.at("output"), pre + "output", "stepspeed needs output PR (pulse and direction)");
}

// One key k of axes.psoN (pre: "axes.psoN.").
void parse_axis_key(const YamlReader& r, const std::string& k, const YAML::Node& key_node, const YAML::Node& v,
                    const std::string& pre, int n, AxisDef* a, Given* given) {
  if (k == "name") {
    a->name = r.topic_name(v, pre + k, "axis");
  } else if (k == "output") {
    parse_output(r, v, pre + k, a);
    given->emplace("output", v);
  } else if (k == "polarity") {
    const std::string m = r.str(v, pre + k);
    if (m == "normal_off") a->polarity = Polarity::NormalOff;
    else if (m == "normal_on") a->polarity = Polarity::NormalOn;
    else r.fail(v, pre + k, "expected normal_off or normal_on");
  } else if (k == "wiring") {
    parse_wiring(r, v, pre + k, n, a);
  } else if (k == "encoder") {
    parse_encoder(r, v, pre + k, &a->encoder);
  } else if (k == "type") {
    const std::string t = r.str(v, pre + k);
    if (t != "linear" && t != "rotary") r.fail(v, pre + k, "expected linear or rotary");
    a->rotary = t == "rotary";
  } else if (k == "units_per_pulse") {
    a->units_per_pulse = r.number(v, pre + k, -kAnyNumber, kAnyNumber);
    if (!(a->units_per_pulse > 0)) r.fail(v, pre + k, "must be > 0");
  } else if (k == "si_per_pulse") {
    a->si_per_pulse = r.number(v, pre + k, -kAnyNumber, kAnyNumber);
    if (!(a->si_per_pulse > 0)) r.fail(v, pre + k, "must be > 0 (m or rad per pulse)");
  } else if (k == "switches") {
    parse_switches(r, v, pre, a);
  } else if (k == "table") {
    a->table_at = table_text(r, v, pre + k, parse_table, &a->table);
    a->has_table = true;
  } else if (k == "params") {
    parse_params(r, v, pre, a, given);
  } else if (k == "stepspeed") {
    a->stepspeed = parse_step_speed(r, v, pre + k);
  } else {
    r.fail(key_node, pre + k,
           "unknown (name, output, polarity, wiring, encoder, type, units_per_pulse, si_per_pulse, switches, "
           "table, params, stepspeed)");
  }
}
}  // namespace

AxesConfig parse_axes_config(const YAML::Node& axes, const std::string& file) {
  const YamlReader r(file);
  AxesConfig cfg;
  cfg.file = file;
  if (!axes || axes.IsNull()) return cfg;
  if (!axes.IsMap()) r.fail(axes, "axes", "expected a map of pso0..pso3");
  for (const auto& kv : axes) {
    const std::string key = kv.first.as<std::string>();
    if (key == "gp0" || key == "gp1") {
      parse_group(r, key, kv.second, &cfg.groups[key[2] - '0']);
      continue;
    }
    if (key.size() != 4 || key.compare(0, 3, "pso") != 0 || key[3] < '0' || key[3] > '3')
      r.fail(kv.first, "axes." + key, "expected pso0, pso1, pso2, pso3, gp0 or gp1");
    const int n = key[3] - '0';
    AxisDef& a = cfg.axes[n];
    a.used = true;
    a.name = key;
    const std::string pre = "axes." + key + ".";
    Given given;
    for (const auto& f : kv.second) parse_axis_key(r, f.first.as<std::string>(), f.first, f.second, pre, n, &a, &given);
    check_stepspeed(r, pre, a, given);
  }
  return cfg;
}

}  // namespace motion
}  // namespace plc_cell
