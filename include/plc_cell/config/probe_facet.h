#pragma once
// A cell extension's scenario probes: the names a scenario reads or drives through it
// ("counter.belt", "axis.slide.position", "temperature.oven"), each a family the extension
// answers for, a name and an optional field. The cell in process (`plc_cell test`) reads
// them over the PLC through this facet; plc_node's scenario target reads the same names
// from the topics the extension's ROS side publishes (ros/extension_ros.h).
//
// What a scenario file may write for a family is known before any cell is built, so each
// family is also declared once for the whole program (ProbeFamilyRegistration): its name,
// and the stimuli its probes take, the units a step drives them in (a temperature channel:
// C, mV, ohm, kohm), with the units its readings may be compared in ("200 C").
#include <cstdint>
#include <optional>
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

// A unit a family's probes are driven in: written as one of spellings (the first is how
// messages list it), handed to ProbeFacet::drive as unit, the value times factor.
struct StimulusUnit {
  std::string unit;                    // "ohm"
  std::vector<std::string> spellings;  // {"kohm", "k\u03a9"}
  double factor = 1;                   // 1000: a kohm is 1000 ohm
};

struct ProbeFamily {
  std::string name;  // "temperature": its probes are temperature.NAME
  std::string what;  // "a temperature channel": how a refusal names one of its probes
  std::vector<StimulusUnit> stimuli;       // empty: a scenario step does not drive it
  std::vector<std::string> reading_units;  // may follow a number compared with a reading
};

// Declares family for as long as the object lives (a static one in the extension's file,
// or one in a test): scenario files naming FAMILY.NAME parse, and their steps may drive its
// probes in its stimuli. Several registrations of one name: the latest counts.
class ProbeFamilyRegistration {
 public:
  explicit ProbeFamilyRegistration(ProbeFamily family);
  explicit ProbeFamilyRegistration(std::string name) : ProbeFamilyRegistration(ProbeFamily{std::move(name), "", {}, {}}) {}
  ~ProbeFamilyRegistration();
  ProbeFamilyRegistration(const ProbeFamilyRegistration&) = delete;
  ProbeFamilyRegistration& operator=(const ProbeFamilyRegistration&) = delete;

 private:
  uint64_t id_;
};

std::optional<ProbeFamily> registered_probe_family(const std::string& name);
std::vector<std::string> registered_probe_families();  // sorted, each once

// A number and a unit of f's stimuli, as a scenario step writes it ("4.096 mV", "10 kohm",
// "5V"): the input drive() gets. Throws Error saying which units f takes.
ProbeInput parse_stimulus(const ProbeFamily& f, const std::string& text);
// "C, mV, ohm or kohm".
std::string stimulus_units(const ProbeFamily& f);

// "%.10g": how every probe prints a number.
std::string probe_number_text(double v);

}  // namespace plc_cell
