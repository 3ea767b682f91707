#pragma once
// A cell extension's scenario probes: the names a scenario reads or drives through it
// ("counter.belt", "axis.slide.position", "temperature.oven"), each a family the extension
// answers for, a name and an optional field. The cell in process (`plc_cell test`) reads
// them over the PLC through this facet; plc_node's scenario target reads the same names
// from the topics the extension's ROS side publishes (ros/extension_ros.h).
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"

namespace plc_cell {

// "axis.slide.position": family "axis", name "slide", field "position"; text as written.
struct ProbeRef {
  std::string family, name, field, text;
};

// What a probe read: a number, and for a state also its word.
struct ProbeReading {
  double number = 0;
  std::string word;   // "idle", "moving", "error" for an axis state; else empty
  bool valid = true;  // false: NaN temperature (line broken), counter or axis unknown
  std::string text;   // how a report prints it ("ON", "-3", "199.8 C", "moving")
};

// A value a scenario drives a probe to: a number, or a quantity in a unit ("C", "mV",
// "ohm", "V", "mA") when one was written.
struct ProbeInput {
  double number = 0;
  bool has_unit = false;
  double value = 0;
  std::string unit;
  std::string text;  // as written
};

class ProbeFacet {
 public:
  virtual ~ProbeFacet() = default;
  // The families it answers for ("counter", "pulse").
  virtual std::vector<std::string> families() const = 0;
  // Why p cannot be read (writing false) or driven (writing true) in this cell, or "".
  // Takes the PLC lock itself.
  virtual std::string check(Plc& plc, const ProbeRef& p, bool writing) const = 0;
  // Takes the PLC lock for the copy.
  virtual ProbeReading read(Plc& plc, const ProbeRef& p) const = 0;
  // Holds p at v from the next scan on; throws plc_cell::Error saying why not.
  virtual void drive(Plc& plc, const ProbeRef& p, const ProbeInput& v) const;
};

// "%.10g": how every probe prints a number.
std::string probe_number_text(double v);

}  // namespace plc_cell
