#pragma once
// FBs analog I/O modules (6AD, 4A2D, 4DA, 2DA) and the B4AD/B2DA/B2A1D expansion
// board of the `modules.analog` section: input
// signals become IR codes (R3840 + n) each scan with the D4006-D4042 format and
// averaging settings; OR codes (R3904 + n) become output signals, forced to zero when
// the CPU has not serviced them for 0.5 s. Any channel may carry the TRi FMD1616's
// conditioning (analog_conditioning.h). Owned by the TemperatureCell (the hook of
// the whole `modules:` section).
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/memory.h"
#include "plc_cell/temp/analog_codes.h"
#include "plc_cell/temp/analog_conditioning.h"

namespace plc_cell {
namespace temp {

struct AnalogInputDef {
  std::string name;
  bool current = false;
  double value = 0;        // a fixed signal, V or mA
  std::string plant;       // or a transmitter on a thermal plant ...
  double plant_lo = 0, plant_hi = 100;  // ... spanning these degC over the range
  bool offset = false;     // ... as 4-20 mA (live zero) instead of 0-20 mA
  ConditioningDef conditioning;  // TRi moving average, gain, zero offset
};
struct AnalogOutputDef {
  std::string name;
  bool current = false;
  ConditioningDef conditioning;  // TRi gain and zero offset (no average)
};
struct AnalogModuleDef {
  std::string type;  // 6AD, 4A2D, 4DA, 2DA
  bool bipolar_code = true, bipolar_signal = true, span10 = true;
  std::vector<AnalogInputDef> inputs;
  std::vector<AnalogOutputDef> outputs;
};
// An FBs-B4AD / B2DA / B2A1D expansion board (manual A:6573-A:6750): in the main
// unit, 0-10 V or 0-20 mA per channel (V or I terminal), 12 bits as 0..16380 in
// D4072-D4075 (inputs) and D4076-D4077 (outputs), every scan, no jumpers.
struct AnalogBoardDef {
  std::string type;  // empty: no board
  std::vector<AnalogInputDef> inputs;
  std::vector<AnalogOutputDef> outputs;
};
constexpr uint32_t kBoardFirstIn = 4072, kBoardFirstOut = 4076;  // D registers
constexpr int32_t kBoardFullCode = 16380;
// Board codes: signal / span x 4095 rounded, x 4 (0..16380, steps of 4, saturating);
// an output code is clamped to 0..16380 and its two low bits are dropped.
int32_t board_input_code(double signal, bool current);
double board_output_signal(int32_t code, bool current);

struct AnalogConfig {
  uint32_t first_ir = 0, first_or = 0;
  std::vector<AnalogModuleDef> modules;
  AnalogBoardDef board;
};

AnalogConfig parse_analog_config(const YAML::Node& analog, const std::string& file);

class AnalogModules {
 public:
  // plant_temperature(name) -> degC of a thermal plant (for transmitters).
  AnalogModules(AnalogConfig cfg, Memory& mem, std::function<double(const std::string&)> plant_temperature);

  void before_inputs(uint64_t now_us);   // output watchdog
  void before_program(uint64_t now_us);  // inputs -> IR
  void after_program(uint64_t now_us);   // OR -> outputs (the CPU services the modules)

  struct Output {
    std::string name;
    uint32_t or_index;  // R3904 + or_index; for a board's output D4076 + or_index
    bool board = false;
    AnalogRange range;
    bool bipolar_code;
    double signal = 0;  // V or mA
    bool watchdog = true;  // forced to zero: not serviced for 0.5 s
  };
  const std::vector<Output>& outputs() const { return outputs_; }
  // The input named so follows signal (V, or mA when current) from the next scan on,
  // instead of its fixed value or transmitter. False with why: no such input, or a
  // voltage given to a current input or the reverse.
  bool drive_input(const std::string& name, double signal, bool current, std::string* why);

 private:
  struct Input {
    AnalogInputDef def;
    uint32_t ir_index;  // R3840 + ir_index; for a board's input D4072 + ir_index
    bool board = false;
    AnalogRange range;
    bool bipolar_code;
    int32_t window[16] = {};
    uint32_t count = 0, next = 0;
    ConditionedChannel conditioning;
  };
  AnalogConfig cfg_;
  Memory& mem_;
  std::function<double(const std::string&)> plant_temperature_;
  std::vector<Input> inputs_;
  std::vector<Output> outputs_;
  std::vector<ConditionedChannel> output_conditioning_;  // parallel to outputs_
  bool serviced_ = false;
  uint64_t last_service_us_ = 0;
};

}  // namespace temp
}  // namespace plc_cell
