#pragma once
// What a scenario reads or drives, named as a user writes it: an address or signal
// ("R0", "DR10:u", "R20:f32", "conveyor_run"), a counter ("counter.belt"), an axis
// ("axis.slide.position", ".state", ".frequency"), a temperature channel
// ("temperature.oven_temp", in degC), an analog input channel ("analog.level", V or mA)
// or the pulse measurement of a counter input ("pulse.X0.period", .width in the configured
// unit, .frequency in Hz).
// The same names mean the same things to every target: the cell in process and plc_node
// through its topics (docs/testing-your-cell.md, "What a condition reads"). Every name but
// an address is a family of a cell extension (config/probe_facet.h): the targets find the
// extension that answers for the family, so a new extension's probes need no change here
// beyond registering the family (ProbeFamilyRegistration).
#include <string>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/probe_facet.h"
#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {
namespace scenario {

// How a scenario file names what it reads: a lone cell's names ("R0", "counter.belt"), or a
// line's, each after the name of its cell ("robot.R0", "robot.counter.belt"; docs/lines.md).
enum class Naming { Cell, Line };

struct Probe {
  enum class Kind { Address, Counter, AxisPosition, AxisState, AxisFrequency, Temperature, Analog,
                    PulseWidth, PulsePeriod, PulseFrequency,
                    Extension };  // a registered family of another extension
  Kind kind = Kind::Address;
  std::string text;  // as written, the key of every report ("R0:u", "axis.slide.state")
  std::string name;  // Address: the address or signal without its format; else the counter,
                     // axis or channel name, or the measured input (X0)
  ValueFormat format = ValueFormat::Default;  // Address only (:s, :u, :hex, :f32)
  std::string family;  // all but Address: "counter", "axis", "pulse", ...
  std::string field;   // "position", "width", ...; empty when the family has none
  std::string cell;    // in a line: the cell ("robot" of "robot.R0"); empty for a lone cell

  ProbeRef ref() const { return ProbeRef{family, name, field, text}; }

  bool operator<(const Probe& o) const { return text < o.text; }
  bool operator==(const Probe& o) const { return text == o.text; }
};

// Throws plc_cell::Error saying why ("unknown kind 'axes.x': counter., axis., temperature.
// or analog."). Whether the name exists in the cell is the target's to say. Named as a
// line names it, the text is CELL.NAME: the cell in `cell`, the rest read as a cell's name
// (text stays the whole name, which every report shows).
Probe parse_probe(const std::string& text, Naming naming = Naming::Cell);

// What a target read: a number, and for the axis state also its word.
using Reading = ProbeReading;

// A probe family beyond the built-in ones (counter, axis, temperature, analog, pulse),
// written FAMILY.NAME or FAMILY.NAME.FIELD, is declared by its extension
// (config/probe_facet.h), with the stimuli its probes take: registered while the object
// lives, so that a scenario file naming it parses; what it reads is the extension's (its
// ProbeFacet, and on plc_node its ROS side's TopicProbes).
using ProbeFamilyRegistration = plc_cell::ProbeFamilyRegistration;

// How reports name p: a bit that is one of the cell's signals shows both, "stop_pb (X1)",
// whichever of the two the scenario wrote; anything else as written.
std::string probe_label(const Probe& p, const CellConfig& cell);

// An address's value v (one read of it: a bit, 16 or 32 bits) as every target reads it in
// format f: a bit ON/OFF, a register signed unless f says otherwise, a float for :f32.
Reading address_reading(const Address& a, uint32_t v, ValueFormat f);

}  // namespace scenario
}  // namespace plc_cell
