#pragma once
// The older FB-series temperature modules in the simulated cell (second source,
// chapter 20): FB-2AJ4/2AK4 (J/K thermocouples), FB-2AH4/2AT4 (3-wire PT-100/PT-1000),
// 4 points each multiplexed through the module's 3rd AI by its 8 DO, and the
// FB-4AJ(K)12/18/24 with 6 points on each of its 5th-8th AIs. The module puts the
// selected point's signal into its temperature AI; FUN72/73/85 (fb_functions.h) drive
// the DO and scale the AI. YAML `modules.fb_temperature`; docs/analog-and-temperature.md.
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/memory.h"
#include "plc_cell/temp/temperature_config.h"

namespace plc_cell {
namespace temp {

struct FbModuleDef {
  std::string type;           // 2AJ4 2AK4 2AH4 2AT4 4AJ12 4AJ18 4AJ24 4AK12 4AK18 4AK24
  bool tc = true, k = true;   // thermocouple, K (else J)
  bool pt1000 = false;        // RTD: PT-1000 (2AT4) or PT-100 (2AH4)
  int points = 4;
  bool bipolar = true, span10 = true;  // JP1 U/B, JP2 10 V / 5 V (the manual's defaults)
  std::string alpha = "DIN";  // the RTD's own curve: DIN or JIS
  uint32_t dout = 0;          // first of its multiplexing DO (Y), YAML `outputs`
  uint32_t first_ai = 0;      // its 1st AI is R3840 + first_ai
  std::vector<ChannelDef> channels;
  bool big() const { return points > 4; }               // an FB-4AJ(K)xx
  int outputs() const { return big() ? 6 : 8; }         // multiplexing DO
  int pl() const { return (bipolar ? 2 : 0) + (span10 ? 0 : 1); }  // FUN72 Pl for these jumpers
  uint32_t temperature_ai(int group) const { return first_ai + (big() ? 4 + group : 2); }
};

struct FbConfig {
  uint32_t first_ai = 0;
  std::vector<FbModuleDef> modules;
};

// `modules.fb_temperature`; throws SourceError at the offending key.
FbConfig parse_fb_config(const YAML::Node& node, const std::string& file);

// The module side of the conversion (plc_cell's model of the lost conversion curves):
// a thermocouple module's AI is linear in temperature with the default factors as its
// calibration (so the defaults read the true temperature), an RTD module's AI is linear
// in resistance over the range of its span; both stop at 1842 (kFbIrCeiling).
int32_t fb_tc_ai(double t_c, bool k, int pl);
int32_t fb_rtd_ai(double t_c, bool pt1000, const std::string& alpha, bool span10);
// The RTD range of a span and curve, degC (B:24-B:45): DIN 10 V -49.8..146.6 ...
void fb_rtd_range(const std::string& alpha, bool span10, double* lo, double* hi);

class FbModules {
 public:
  FbModules(FbConfig cfg, Memory& mem, std::function<double(const std::string&)> plant_temperature);

  // Each temperature AI takes the signal of the point its DO select (exactly one
  // point's pair on; otherwise the input is open and reads 2047).
  void before_program();
  const FbConfig& config() const { return cfg_; }
  void set_open(size_t module, size_t point, bool open);  // tests, fault injection

 private:
  int32_t signal(const FbModuleDef& m, size_t point) const;

  FbConfig cfg_;
  Memory& mem_;
  std::function<double(const std::string&)> plant_temperature_;
};

}  // namespace temp
}  // namespace plc_cell
