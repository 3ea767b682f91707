#pragma once
// The `modules:` section as one ScanHook: the FBs temperature modules, the thermal
// plants behind them, and the analog I/O modules (analog_modules.h). plants advance and modules sample in virtual time before each scan's input
// image; readings, working registers and the configuration table are written into PLC
// memory before the program runs. docs/analog-and-temperature.md.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/temp/temperature_config.h"
#include "plc_cell/temp/thermal_plant.h"

namespace plc_cell {
namespace temp {

// What the readings register holds for a broken line (the manual has "the line broken
// value" without a number; plc_cell's choice).
constexpr int16_t kLineBrokenValue = 32767;
constexpr uint16_t kExecMeasuring = 0x56;  // WR+0 high byte: all channels read

// The special registers of FBs temperature measurement and FUN86 (manual A:6941, A:7165).
namespace treg {
constexpr uint32_t kPvFromR4004 = 4003, kPvStart = 4004, kIntervals = 4005, kLargePower = 4006,
                   kLargePowerTime = 4007, kHighAlarm = 4008, kInstalled = 4010, kPidEnable = 4012;
// FB generation only (second source B:383-B:440, B:876-B:913).
constexpr uint32_t kFbFun85 = 4000,  // R4000 (signature, averaging) .. R4004 (ms per point)
    kFbSlotMs = 4014, kFbAveraging = 4015, kFbFactors = 4016, kFbRtd = 4020, kFbRtdFactors = 4022;
}

class FbModules;

struct ChannelState {
  std::string name;
  int module = 0;
  double value_c = 0;   // averaged reading, degC; NaN before the first sample
  bool open = false;    // broken line (sensor or wire)
  bool out_of_range = false;
  std::vector<double> window;  // the moving average's samples
  size_t next = 0;
  double resolution_c = 0.1;
};

// One channel as the PLC's own registers show it, which is what a program (and so a
// robot stack) sees: the reading register in 0.1 of the modules' unit, the installed and
// abnormal bits, and the same in degrees Celsius for topics that are SI.
struct ChannelReading {
  int16_t raw = 0;
  bool installed = false;
  bool abnormal = false;    // the module's out-of-range bit
  bool broken = false;      // not installed, or the line-broken value
  double celsius = 0;       // NaN when broken
  double variance_c2 = 0;   // of celsius: rounding to the channel's step q gives q^2/12
  // "not installed", "line broken", "out of range", or the reading in the modules' unit.
  std::string state() const;
};

class TemperatureCell final : public ScanHook {
 public:
  TemperatureCell(TemperatureConfig cfg, Memory& mem);
  ~TemperatureCell() override;  // out of line: the FB modules are an incomplete type here
  TemperatureCell(const TemperatureCell&) = delete;
  TemperatureCell& operator=(const TemperatureCell&) = delete;

  void before_inputs(uint64_t now_us) override;   // plants and sampling
  void before_program(uint64_t now_us) override;  // readings and registers into memory
  void after_program(uint64_t now_us) override;   // analog outputs take the OR values
  void attached(ScanEngine& e) override;           // FUN86 finds it: temperature_cell_of
  void detached(ScanEngine& e) override;

  // The analog I/O modules of modules.analog, or nullptr.
  const AnalogModules* analog() const { return analog_.get(); }
  // The FB-series modules of modules.fb_temperature, or nullptr.
  FbModules* fb() { return fb_.get(); }

  const TemperatureConfig& config() const { return cfg_; }
  const std::vector<ChannelState>& channels() const { return channels_; }
  ThermalPlant* plant(const std::string& name);
  bool all_read() const { return all_read_; }
  // Every channel decoded from m (the PLC's memory, its lock held: a copy and no more).
  std::vector<ChannelReading> readings(const Memory& m) const;
  // Breaks or mends a channel's sensor line (tests, fault injection).
  void set_open(size_t channel, bool open) { wired_open_.at(channel) = open; }
  // The channel named so (a channel's `name:`), or -1.
  int channel_index(const std::string& name) const;
  // Drives channel ch from now on with a temperature (C) or its sensor's own signal (mV,
  // ohm), instead of its plant or fixed value: how a test ramps what the sensor sees.
  // False with why for a unit the channel's sensor cannot give.
  bool drive_channel(size_t ch, const Quantity& q, std::string* why);
  // Drives the analog input named so (modules.analog) with a signal in V or mA instead of
  // its fixed value or transmitter. False with why (no such input, the wrong unit).
  bool drive_analog_input(const std::string& name, const Quantity& q, std::string* why);
  // The engineering value a reading register holds for degC (unit, resolution, rounding).
  int16_t register_value(double c, double resolution_c) const;

 private:
  double true_temperature(size_t ch) const;
  double sense(const ModuleDef& m, double true_c, bool* out_of_range) const;
  // What the module reads from a fixed signal in the sensor's unit (mV, ohm).
  double sense_signal(const ModuleDef& m, const Quantity& signal, bool* out_of_range) const;
  void sample(size_t ch);
  void write_registers();

  TemperatureConfig cfg_;
  Memory& mem_;
  std::vector<ThermalPlant> plants_;
  std::vector<PlantDef> plant_defs_;
  std::vector<int> plant_of_;  // per channel, -1 = fixed temperature
  std::vector<ChannelState> channels_;
  std::vector<bool> wired_open_;
  struct ModuleState {
    size_t first = 0;   // global channel index
    int count = 0;
    uint64_t slot_us = 0;  // one channel's share of the update period
    uint64_t next_slot = 0;  // index of the next slot to sample
    int current = 0;
    uint32_t reads = 0;
  };
  std::vector<ModuleState> modules_;
  std::unique_ptr<AnalogModules> analog_;
  std::unique_ptr<FbModules> fb_;
  bool all_read_ = false;
  bool have_time_ = false;
  uint64_t last_us_ = 0;
};

// The cell's temperature subsystem from its config document (nullptr when the cell
// has no modules section).
std::unique_ptr<TemperatureCell> make_temperature_cell(const YAML::Node& document, const std::string& file,
                                                       Memory& mem);

}  // namespace temp
}  // namespace plc_cell

namespace plc_cell {
namespace temp {
// The temperature subsystem hooked to a PLC's scan engine, for FUN86 (which must find
// the readings and know when all channels have been read); nullptr if none.
const TemperatureCell* temperature_cell_of(const ScanEngine* engine);
}  // namespace temp
}  // namespace plc_cell
