#include "plc_cell/scenario/property_watcher.h"

#include <algorithm>

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

namespace {

// Every name a condition reads, once.
void names_of(const Condition& c, std::vector<const Probe*>* out) {
  for (const Comparison& cmp : c.all)
    for (const Probe* p : cmp.probes())
      if (std::none_of(out->begin(), out->end(), [&](const Probe* q) { return q->text == p->text; }))
        out->push_back(p);
}

}  // namespace

PropertyWatcher::PropertyWatcher(std::vector<Property> properties,
                                 const std::function<WatchedAddress(const Probe&)>& resolve, std::string source,
                                 std::string how, bool history)
    : properties_(std::move(properties)), source_(std::move(source)), how_(std::move(how)), history_(history) {
  std::vector<Diagnostic> errors;
  for (const Property& p : properties_) {
    Track t(p);
    std::vector<const Probe*> names;
    names_of(p.when, &names);
    names_of(p.cond, &names);
    for (const Probe* probe : names) {
      const auto same = std::find_if(slots_.begin(), slots_.end(), [&](const Slot& s) { return s.probe.text == probe->text; });
      if (same != slots_.end()) {
        t.slots.push_back(size_t(same - slots_.begin()));
        continue;
      }
      WatchedAddress at;
      try {
        at = resolve(*probe);
      } catch (const Error& e) {
        Diagnostic d;
        d.where.file = p.file;
        d.where.line = p.line;
        d.message = "property '" + p.text + "': " + e.what();
        errors.push_back(std::move(d));
        continue;
      }
      if (addresses_.size() <= at.cell) {
        addresses_.resize(at.cell + 1);
        slot_of_.resize(at.cell + 1);
      }
      Slot s;
      s.probe = *probe;
      s.cell = at.cell;
      s.index = addresses_[at.cell].size();
      s.reading = address_reading(at.address, 0, probe->format);
      addresses_[at.cell].push_back(at.address);
      slot_of_[at.cell].push_back(slots_.size());
      t.slots.push_back(slots_.size());
      slots_.push_back(std::move(s));
    }
    tracks_.push_back(std::move(t));
  }
  if (!errors.empty()) throw SourceError(errors);
}

const std::vector<Address>& PropertyWatcher::addresses(size_t cell) const {
  static const std::vector<Address> none;
  return cell < addresses_.size() ? addresses_[cell] : none;
}

void PropertyWatcher::scanned(size_t cell, uint64_t t_us, const uint32_t* values) {
  std::lock_guard<std::mutex> lk(mu_);
  // The instant before this one is complete: every cell that scans at it has scanned.
  if (pending_ && t_us > pending_us_) evaluate(pending_us_);
  if (!pending_ || t_us > pending_us_) pending_us_ = std::max(t_us, last_us_);
  pending_ = true;
  if (cell >= slot_of_.size()) return;
  const std::vector<size_t>& slots = slot_of_[cell];
  for (size_t k = 0; k < slots.size(); ++k) {
    Slot& s = slots_[slots[k]];
    if (s.raw == values[k]) continue;
    // The reading (and its text) is made when the value changes, not at every instant.
    s.raw = values[k];
    s.reading = address_reading(addresses_[cell][k], s.raw, s.probe.format);
  }
}

void PropertyWatcher::flush() {
  std::lock_guard<std::mutex> lk(mu_);
  if (pending_) evaluate(pending_us_);
}

void PropertyWatcher::evaluate(uint64_t t_us) {
  pending_ = false;
  if (!evaluated_) first_us_ = t_us;
  evaluated_ = true;
  last_us_ = t_us;
  for (Track& t : tracks_) {
    const auto read = [&](const Probe& p) -> Reading {
      for (size_t s : t.slots)
        if (slots_[s].probe.text == p.text) return slots_[s].reading;
      Reading unknown;  // a name that did not resolve: the constructor threw
      unknown.valid = false;
      return unknown;
    };
    const bool now = t.property->violated([&](const Condition& c) {
      return std::all_of(c.all.begin(), c.all.end(), [&](const Comparison& cmp) { return cmp.holds(read); });
    });
    const bool failed = t.watch.failed(now, t_us);
    if (now && !t.violated) {
      t.current = Episode();
      t.current.begin_us = t_us;
      for (size_t s : t.slots) t.current.values.push_back({slots_[s].probe.text, slots_[s].reading.text});
    }
    t.violated = now;
    if (failed && !t.counted) {
      t.counted = true;
      ++t.count;
      t.current.counted_us = t_us;
      if (!history_) t.episodes.clear();
      t.episodes.push_back(t.current);
    } else if (!now && t.counted) {
      t.counted = false;
      t.episodes.back().end_us = t_us;
    }
  }
}

monitor::PropertyStatus PropertyWatcher::status(const Track& t, uint64_t at_us) const {
  monitor::PropertyStatus s;
  s.text = t.property->text;
  s.where = t.property->file + ":" + std::to_string(t.property->line);
  s.within_us = t.property->within_us;
  // The violations counted at or before at_us.
  const auto end = std::upper_bound(t.episodes.begin(), t.episodes.end(), at_us,
                                    [](uint64_t at, const Episode& e) { return at < e.counted_us; });
  s.violations = history_ ? uint64_t(end - t.episodes.begin()) : t.count;
  if (end == t.episodes.begin()) return s;
  const Episode& last = *(end - 1);
  s.last_begin_us = last.begin_us;
  s.last_ongoing = last.end_us > at_us;
  s.last_duration_us = (s.last_ongoing ? at_us : last.end_us) - last.begin_us;
  s.last_values = last.values;
  s.violated = s.last_ongoing;
  s.since_us = last.begin_us;
  return s;
}

monitor::PropertyReport PropertyWatcher::empty_report() const {
  monitor::PropertyReport r;
  r.source = source_;
  r.how = how_;
  return r;
}

monitor::PropertyReport PropertyWatcher::report() const {
  monitor::PropertyReport r = empty_report();
  std::lock_guard<std::mutex> lk(mu_);
  r.evaluated = evaluated_;
  r.t_us = last_us_;
  for (const Track& t : tracks_) r.properties.push_back(status(t, last_us_));
  return r;
}

monitor::PropertyReport PropertyWatcher::report_at(uint64_t t_us) const {
  if (!history_) return report();
  monitor::PropertyReport r = empty_report();
  std::lock_guard<std::mutex> lk(mu_);
  r.evaluated = evaluated_ && t_us >= first_us_;
  r.t_us = std::min(t_us, last_us_);
  for (const Track& t : tracks_) r.properties.push_back(status(t, r.t_us));
  return r;
}

}  // namespace scenario
}  // namespace plc_cell
