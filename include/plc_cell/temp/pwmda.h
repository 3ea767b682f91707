#pragma once
// The PWMDA single-point analog output (manual Appendix 2, A:474-A:553): a component
// in place of a high-speed transistor output that filters FUN139's pulse train into
// 0-10 V. A ScanHook so the voltage settles in virtual time. docs/analog-and-temperature.md.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "plc_cell/core/memory.h"
#include "plc_cell/core/scan_engine.h"

namespace plc_cell {
namespace temp {

constexpr double kPwmdaFullScaleV = 11.41;  // uncalibrated: width 1000 -> 11.41 V (879 -> 10 V)
constexpr double kPwmdaTimeConstantS = 0.01;  // plc_cell's: "< 50 ms" conversion = 5 tau

struct PwmdaDef {
  std::string name;
  int pw = 0;             // Y0 -> 0, Y2 -> 1, Y4 -> 2, Y6 -> 3
  bool trimmed = false;   // Rv adjusted so that full duty gives 10 V (the manual's curve A)
};

// The settled output voltage for a duty (0..1).
double pwmda_voltage(double duty, bool trimmed);

std::vector<PwmdaDef> parse_pwmda_config(const YAML::Node& node, const std::string& file);

class PwmdaOutputs final : public ScanHook {
 public:
  explicit PwmdaOutputs(std::vector<PwmdaDef> defs);
  // The filters follow the pulse trains the last scan's FUN139 left (in STOP too:
  // the output decays).
  void before_inputs(uint64_t now_us) override;
  void on_stop() override;                       // STOP switches the pulse trains off
  void attached(ScanEngine& e) override;         // the PLC whose FUN139 drives the filters
  void detached(ScanEngine& e) override;

  const std::vector<PwmdaDef>& defs() const { return defs_; }
  double voltage(size_t k) const { return volts_.at(k); }

 private:
  std::vector<PwmdaDef> defs_;
  ScanEngine* engine_ = nullptr;
  std::vector<double> volts_;
  bool have_time_ = false;
  uint64_t last_us_ = 0;
};

// modules.pwmda of the cell document (nullptr when there is none).
std::unique_ptr<PwmdaOutputs> make_pwmda_outputs(const YAML::Node& document, const std::string& file);

}  // namespace temp
}  // namespace plc_cell
