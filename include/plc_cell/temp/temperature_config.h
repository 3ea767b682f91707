#pragma once
// The `modules:` section of the cell YAML: temperature modules, their channels and the
// thermal plants that the simulated cell puts behind them. docs/analog-and-temperature.md.
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/address.h"
#include "plc_cell/temp/analog_modules.h"
#include "plc_cell/temp/ntc.h"
#include "plc_cell/temp/sensor_signal.h"
#include "plc_cell/temp/thermal_plant.h"
#include "plc_cell/temp/thermocouple.h"

namespace plc_cell {
namespace temp {

// The PLC generation whose temperature instructions and R4000-R4023 meanings the cell
// has (`modules.generation`): FBs (default) or the older FB series (FUN72/73/85 and the
// FB FUN86, FB-2A?4 / FB-4AJ(K)xx modules). The two clash on FUN86 and R4003-R4008.
enum class Generation { FBs, FB };

struct FbConfig;  // fb_modules.h

enum class ModuleKind { TC2, TC6, TC16, RTD6, RTD16, NTC6, A4TC2, A4RTD2 };
enum class SensorKind { Thermocouple, Pt100, Pt1000, Ntc };

struct ModuleInfo {
  const char* name;  // as on WinProladder's screen: "6TC", "2A4RTD", ...
  int channels;
  int code;             // module-name code in SR+4.. (plc_cell's numbering, the manual has none)
  double fast_s, normal_s;  // update period of all its channels (manual "conversion time")
  int irs;              // numeric input registers its temperature part occupies
};
const ModuleInfo& module_info(ModuleKind k);

struct ChannelDef {
  std::string name;   // ROS frame_id and topic name; empty = not published
  std::string plant;  // the thermal plant it measures, or empty
  double fixed_c = 25;  // the temperature when no plant is given
  bool open = false;    // a broken sensor line
  // `value`: a fixed signal in the sensor's unit instead (mV for a thermocouple, the emf
  // of its hot junction against 0 degC as the NIST tables give it; ohm for an RTD or NTC).
  bool has_signal = false;
  Quantity signal;
};

struct ModuleDef {
  ModuleKind kind = ModuleKind::TC6;
  SensorKind sensor = SensorKind::Thermocouple;
  TcType tc = TcType::K;
  std::string alpha = "DIN";          // RTD: DIN (0.00385) or JIS (0.003916)
  NtcBeta ntc{10000, 3950};
  bool use_sh = false;                // 6NTC: Steinhart-Hart coefficients instead of beta
  SteinhartHart sh{};
  double cold_junction_c = 25;        // the module's terminal temperature
  std::vector<ChannelDef> channels;   // at most module_info(kind).channels; the rest are unwired
  int sensor_code() const;            // high byte of SR+4..: plc_cell's numbering
};

struct PlantDef {
  std::string name;
  ThermalPlantParams params;
  bool has_heater = false, heater_analog = false;
  Address heater{};  // a Y/M bit (its on-time is the power) or a register (value / full_scale)
  bool has_cooler = false, cooler_analog = false;
  Address cooler{};
  double full_scale = 16383;
};

// A PID loop whose set point and gains ROS may change (FUN86 reads them from registers).
struct LoopDef {
  std::string name;
  Address sv{}, kc{}, ki{}, td{};
  bool has_kc = false, has_ki = false, has_td = false;
};

struct TemperatureConfig {
  Generation generation = Generation::FBs;
  std::shared_ptr<const FbConfig> fb;  // modules.fb_temperature (FB generation), or null
  bool fast = false;        // Fast: half the update period, 1 degree resolution
  bool fahrenheit = false;  // readings in 0.1 degF
  int averaging = 1;        // moving average over 1, 2, 4, 8 (NTC also 16) samples
  Address readings = parse_address("R0");  // SR+2: one word per channel, 0.1 degree
  Address working = parse_address("D0");   // WR: 4 + 4 N words
  bool has_table = false;
  Address table{};          // SR: 4 + N words, written as WinProladder would
  uint32_t first_ir = 0;    // IR (R3840 + n) of the first module
  std::vector<ModuleDef> modules;
  std::vector<PlantDef> plants;
  std::vector<LoopDef> loops;
  bool has_analog = false;
  AnalogConfig analog;  // modules.analog
  int total_channels() const;
};

// Reads node (the `modules:` mapping); throws SourceError at the offending key.
TemperatureConfig parse_temperature_config(const YAML::Node& modules, const std::string& file);

// One entry of a module's `channels` list ({name, plant, temperature, open}).
ChannelDef parse_channel_def(const YAML::Node& n, const std::string& key, const std::string& file);

// modules.generation of a whole cell document (FBs when absent); throws SourceError.
Generation cell_generation(const YAML::Node& document, const std::string& file);

}  // namespace temp
}  // namespace plc_cell
