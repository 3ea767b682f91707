#pragma once
// A scenario file's properties watched over a run that is not a test: a line running in
// real time, a line's recording (docs/monitor.md, "Properties"). It is the board the
// monitor's overview reads: per property its state, how often it was violated and its last
// violation. A violation counts as the runner counts one (property.h): once it has lasted
// longer than its grace (within:); it began at the first instant the property was violated
// and ends at the first instant it holds again.
//
// The names are addresses and signals of the cells (CELL.NAME on a line): whoever runs the
// cells reads them after each scan, in one memory read, and hands their values to
// scanned(). The instant of a scan is evaluated when a later instant arrives, so that the
// cells scanned one after another at one instant are seen together.
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/monitor/property_board.h"
#include "plc_cell/scenario/property.h"

namespace plc_cell {
namespace scenario {

// Where a name of a property is read: its cell (the line's or the monitor's numbering) and
// the address there.
struct WatchedAddress {
  size_t cell = 0;
  Address address;
};

class PropertyWatcher : public monitor::PropertyBoard {
 public:
  // resolve: each name's cell and address, or throws Error saying why (a name of a
  // family such as counter.X, an unknown cell or signal). Throws SourceError with every
  // such error at its property's file:line. history: keep every violation, for
  // report_at (a recording); otherwise only the last.
  PropertyWatcher(std::vector<Property> properties, const std::function<WatchedAddress(const Probe&)>& resolve,
                  std::string source, std::string how, bool history = false);

  size_t size() const { return tracks_.size(); }
  // The addresses of cell's names, in the order scanned() takes their values (empty for a
  // cell no property names).
  const std::vector<Address>& addresses(size_t cell) const;
  // After a scan of cell at t_us: values[k] is addresses(cell)[k] as Memory::read gives
  // it. An earlier t_us than the last one's is taken as the last one's (cells on clocks of
  // their own). Any thread.
  void scanned(size_t cell, uint64_t t_us, const uint32_t* values);
  // Evaluates the instant still pending (the end of a recording).
  void flush();

  monitor::PropertyReport report() const override;
  monitor::PropertyReport report_at(uint64_t t_us) const override;

 private:
  struct Slot {
    Probe probe;
    size_t cell = 0, index = 0;  // addresses_[cell][index]
    uint32_t raw = 0;
    Reading reading;
  };
  struct Episode {
    uint64_t begin_us = 0, counted_us = 0, end_us = UINT64_MAX;  // UINT64_MAX: goes on
    std::vector<monitor::NamedValue> values;
  };
  struct Track {
    explicit Track(const Property& p) : property(&p), watch(p) {}
    const Property* property;  // in properties_
    std::vector<size_t> slots;  // its names'
    PropertyWatch watch;
    bool violated = false;  // at the last instant, grace or not
    bool counted = false;   // the violation going on counts
    Episode current;
    uint64_t count = 0;
    std::vector<Episode> episodes;  // counted ones: every one (history) or the last
  };
  void evaluate(uint64_t t_us);
  monitor::PropertyStatus status(const Track& t, uint64_t at_us) const;
  monitor::PropertyReport empty_report() const;

  std::vector<Property> properties_;  // never resized: the tracks point into it
  std::vector<Slot> slots_;
  std::vector<std::vector<Address>> addresses_;
  std::vector<std::vector<size_t>> slot_of_;  // [cell][index] -> slot
  std::vector<Track> tracks_;
  std::string source_, how_;
  bool history_;
  mutable std::mutex mu_;
  bool pending_ = false, evaluated_ = false;
  uint64_t pending_us_ = 0, last_us_ = 0, first_us_ = 0;
};

}  // namespace scenario
}  // namespace plc_cell
