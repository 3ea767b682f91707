// The FB-series temperature modules: YAML, the modules' conversion, and the multiplexer
// that follows the DO (fb_modules.h).
#include "plc_cell/temp/fb_modules.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/config/yaml_reader.h"
#include "plc_cell/temp/fb_tc_scaling.h"
#include "plc_cell/temp/rtd.h"

namespace plc_cell {
namespace temp {

FbConfig parse_fb_config(const YAML::Node& node, const std::string& file) {
  const YamlReader r(file);
  const std::string k = "modules.fb_temperature";
  FbConfig c;
  r.only(node, k, {"first_ai", "modules"});
  if (node["first_ai"]) c.first_ai = uint32_t(r.number(node["first_ai"], k + ".first_ai", 0, 63));
  const YAML::Node ms = node["modules"];
  if (!ms || !ms.IsSequence() || ms.size() == 0 || ms.size() > 8) r.fail(ms ? ms : node, k + ".modules", "a list of 1 to 8 modules");
  uint32_t ai = c.first_ai;
  for (size_t i = 0; i < ms.size(); ++i) {
    const YAML::Node& n = ms[i];
    const std::string mk = k + ".modules[" + std::to_string(i) + "]";
    r.only(n, mk, {"type", "outputs", "polarity", "span", "alpha", "channels"});
    FbModuleDef m;
    if (!n["type"]) r.fail(n, mk + ".type", "missing");
    m.type = r.str(n["type"], mk + ".type");
    const std::string& t = m.type;
    if (t == "2AJ4" || t == "2AK4" || t == "2AH4" || t == "2AT4") {
      m.tc = t[2] == 'J' || t[2] == 'K';
      m.k = t[2] == 'K';
      m.pt1000 = t[2] == 'T';
    } else if (t.size() == 5 && t.compare(0, 2, "4A") == 0 && (t[2] == 'J' || t[2] == 'K') &&
               (t.substr(3) == "12" || t.substr(3) == "18" || t.substr(3) == "24")) {
      m.k = t[2] == 'K';
      m.points = std::stoi(t.substr(3));
    } else {
      r.fail(n["type"], mk + ".type", "unknown module '" + t + "' (2AJ4, 2AK4, 2AH4, 2AT4, 4AJ12/18/24, 4AK12/18/24)");
    }
    if (m.big() && ms.size() > 1)
      r.fail(n["type"], mk + ".type", "an FB-" + t + " must be installed alone (no other AI or temperature module)");
    if (!n["outputs"]) r.fail(n, mk + ".outputs", "missing: the first of the module's multiplexing DO, e.g. Y16");
    const Address y = r.address(n["outputs"], mk + ".outputs");
    if (y.area != Area::Y || y.width != Width::Bit || y.index + uint32_t(m.outputs()) > 256)
      r.fail(n["outputs"], mk + ".outputs", "expected Y0..Y" + std::to_string(256 - m.outputs()) + " (" +
                                              std::to_string(m.outputs()) + " DO)");
    m.dout = y.index;
    if (n["polarity"]) {
      const std::string p = r.str(n["polarity"], mk + ".polarity");
      if (p != "bipolar" && p != "unipolar") r.fail(n["polarity"], mk + ".polarity", "bipolar or unipolar");
      if (!m.tc && p == "unipolar") r.fail(n["polarity"], mk + ".polarity", "an FB-" + t + " is bipolar only");
      m.bipolar = p == "bipolar";
    }
    if (n["span"]) {
      const double s = r.number(n["span"], mk + ".span", 5, 10);
      if (s != 5 && s != 10) r.fail(n["span"], mk + ".span", "5 or 10 (V)");
      m.span10 = s == 10;
    }
    if (n["alpha"]) {
      m.alpha = r.str(n["alpha"], mk + ".alpha");
      if (m.tc || (m.alpha != "DIN" && m.alpha != "JIS")) r.fail(n["alpha"], mk + ".alpha", "DIN or JIS, RTD modules only");
    }
    if (const YAML::Node ch = n["channels"]) {
      if (!ch.IsSequence() || int(ch.size()) > m.points)
        r.fail(ch, mk + ".channels", "a list of at most " + std::to_string(m.points) + " points");
      for (size_t j = 0; j < ch.size(); ++j) {
        const std::string ck = mk + ".channels[" + std::to_string(j) + "]";
        m.channels.push_back(parse_channel_def(ch[j], ck, file));
        // The FB modules' conversion is a linear model in degC (fb_measure.h), not a sensor curve.
        if (m.channels.back().has_signal)
          r.fail(ch[j]["value"], ck + ".value", "the FB-series modules take a value in C only (mV and ohm are for the FBs modules)");
      }
    }
    m.first_ai = ai;
    ai += m.big() ? 8 : 3;  // a 2A?4 takes 3 AI addresses; a 4AJ(K)xx 4 general + 4 temperature
    if (ai > 64) r.fail(n, mk, "its AIs go past R3903");
    c.modules.push_back(m);
  }
  return c;
}

int32_t fb_tc_ai(double t_c, bool k, int pl) {
  const FbTc tc = k ? FbTc::K : FbTc::J;
  double counts;
  if (t_c >= 0)
    counts = t_c * 1024.0 / ((fb_bipolar(pl) ? 2.0 : 1.0) * fb_default_pos_factor(tc, pl, true));
  else
    counts = fb_bipolar(pl) ? t_c * 1024.0 / ((fb_span10(pl) ? 2.0 : 1.0) * fb_default_neg_factor(tc)) : 0.0;
  const double ai = std::round(fb_bipolar(pl) ? counts : counts - 2048);
  return int32_t(std::clamp(ai, -2048.0, double(kFbIrCeiling)));
}

void fb_rtd_range(const std::string& alpha, bool span10, double* lo, double* hi) {
  const bool jis = alpha == "JIS";
  *lo = span10 ? (jis ? -50.7 : -49.8) : (jis ? -12.5 : -12.3);
  *hi = span10 ? (jis ? 149.2 : 146.6) : (jis ? 85.1 : 83.6);
}

int32_t fb_rtd_ai(double t_c, bool pt1000, const std::string& alpha, bool span10) {
  const RtdCurve k = rtd_curve(pt1000 ? 1000 : 100, alpha);
  double lo, hi;
  fb_rtd_range(alpha, span10, &lo, &hi);
  const double rlo = rtd_resistance(k, lo), rhi = rtd_resistance(k, hi);
  const double ai = std::round(-2048 + (rtd_resistance(k, t_c) - rlo) / (rhi - rlo) * (kFbIrCeiling + 2048));
  return int32_t(std::clamp(ai, -2048.0, double(kFbIrCeiling)));
}

FbModules::FbModules(FbConfig cfg, Memory& mem, std::function<double(const std::string&)> plant_temperature)
    : cfg_(std::move(cfg)), mem_(mem), plant_temperature_(std::move(plant_temperature)) {}

void FbModules::set_open(size_t module, size_t point, bool open) {
  auto& chs = cfg_.modules.at(module).channels;
  if (point >= chs.size()) chs.resize(point + 1);
  chs[point].open = open;
}

int32_t FbModules::signal(const FbModuleDef& m, size_t point) const {
  if (point >= m.channels.size() || m.channels[point].open) return kFbIrOpen;  // unwired or broken
  const ChannelDef& ch = m.channels[point];
  const double t = ch.plant.empty() ? ch.fixed_c : plant_temperature_(ch.plant);
  return m.tc ? fb_tc_ai(t, m.k, m.pl()) : fb_rtd_ai(t, m.pt1000, m.alpha, m.span10);
}

void FbModules::before_program() {
  for (const FbModuleDef& m : cfg_.modules) {
    // The DO pattern: a 2A?4 switches point i with the pair Ym+2i, Ym+2i+1; an
    // FB-4AJ(K)xx point k of every group with Ym+k (plc_cell's reading: the figure is lost).
    int selected = -1, on = 0;
    for (int b = 0; b < m.outputs(); ++b)
      if (mem_.bit(Area::Y, m.dout + uint32_t(b))) ++on, selected = m.big() ? b : b / 2;
    const bool one = m.big() ? on == 1 : on == 2 && mem_.bit(Area::Y, m.dout + 2 * uint32_t(selected)) &&
                                             mem_.bit(Area::Y, m.dout + 2 * uint32_t(selected) + 1);
    const int groups = m.big() ? 4 : 1;
    for (int g = 0; g < groups; ++g) {
      const size_t point = size_t(g * (m.big() ? 6 : 4) + selected);
      const bool wired = one && int(point) < m.points;
      mem_.set_reg(Area::R, 3840 + m.temperature_ai(g), uint16_t(wired ? signal(m, point) : kFbIrOpen));
    }
  }
}

}  // namespace temp
}  // namespace plc_cell
