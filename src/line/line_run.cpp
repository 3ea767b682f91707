// Running a line: its cells in RUN, the wires' ends connected, and the cells scanned on
// one virtual clock (scan_at) or in real time (start_real_time).
#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/line/line.h"

namespace plc_cell {
namespace line {

// Every cell here in RUN, then the ends of the wires: a tap's first value is its source's
// after RUN's clearing (a retentive register keeps its own), a sink's is that value through
// the wire. A source elsewhere starts at 0.
void Line::connect() {
  taps_.assign(size(), WireTaps());
  tap_wire_.assign(size(), {});
  sinks_.clear();
  sinks_.resize(wires_.size());
  twin_sinks_.clear();
  twin_sinks_.resize(wires_.size());
  for (size_t i = 0; i < size(); ++i)
    if (here(i) && !cells_[i]->plc().set_mode(RunMode::Run))
      throw Error("cell " + entry(i).name + ": cannot RUN: no program loaded");
  for (size_t w = 0; w < wires_.size(); ++w) {
    Wire& wire = wires_[w];
    if (here(wire.from_cell)) {
      wire.initial = cells_[wire.from_cell]->plc().locked([&](ScanEngine&, Memory& m) { return m.read(wire.from); });
      taps_[wire.from_cell].add(wire.from, wire.initial);
      tap_wire_[wire.from_cell].push_back(w);
    }
    if (here(wire.to_cell)) {
      Cell& to = *cells_[wire.to_cell];
      sinks_[w] = to.plc().locked([&](ScanEngine& e, Memory& m) {
        return WireSink::make(to.soft(), e, m, wire.to, wire.model, wire.initial);
      });
      // A wire drives the cell's simulation and memory directly: its lockstep twin's too.
      if (SoftCell* twin = to.twin())
        twin_sinks_[w] = twin->plc().locked([&](ScanEngine& e, Memory& m) {
          return WireSink::make(*twin, e, m, wire.to, wire.model, wire.initial);
        });
    }
  }
}

void Line::run() {
  connect();
  due_us_.assign(size(), 0);
  inbox_.assign(size(), {});
  group_cells();
}

void Line::carry(size_t cell) {
  auto& pending = taps_[cell].pending();
  const std::vector<size_t>& wire_of = tap_wire_[cell];
  if (!real_time_) {
    for (const WireTaps::Sample& p : pending) {
      const size_t w = wire_of[p.tap];
      if (sinks_[w]) inbox_[wires_[w].to_cell].push_back({p.t_us, cell, w, p.value});
      else if (on_remote_) on_remote_(w, p.t_us, p.value);
    }
    pending.clear();
    return;
  }
  // The samples for one sink cell in a row are delivered under one lock (its twin's after).
  for (size_t k = 0; k < pending.size();) {
    const size_t w = wire_of[pending[k].tap];
    if (!sinks_[w]) {
      if (on_remote_) on_remote_(w, pending[k].t_us, pending[k].value);
      ++k;
      continue;
    }
    const size_t to = wires_[w].to_cell;
    size_t end = k + 1;
    while (end < pending.size() && sinks_[wire_of[pending[end].tap]] && wires_[wire_of[pending[end].tap]].to_cell == to)
      ++end;
    const auto each = [&](const std::vector<std::unique_ptr<WireSink>>& sinks, Plc& plc) {
      plc.locked([&](ScanEngine& e, Memory&) {
        for (size_t j = k; j < end; ++j)
          sinks[wire_of[pending[j].tap]]->receive(e.now_us(), pending[j].value);
        return 0;
      });
    };
    each(sinks_, cells_[to]->plc());
    if (SoftCell* twin = cells_[to]->twin()) each(twin_sinks_, twin->plc());
    k = end;
  }
  pending.clear();
}

// In virtual time the sink shares the source's clock; in real time each cell's clock is its
// own, and the delay runs from the value's arrival (t_us UINT64_MAX: the sink's now).
void Line::deliver(size_t w, uint64_t t_us, uint32_t value) {
  Cell& to = *cells_[wires_[w].to_cell];
  to.plc().locked([&](ScanEngine& e, Memory&) {
    sinks_[w]->receive(t_us == UINT64_MAX ? e.now_us() : t_us, value);
    return 0;
  });
  if (twin_sinks_[w])
    to.twin()->plc().locked([&](ScanEngine& e, Memory&) {
      twin_sinks_[w]->receive(t_us == UINT64_MAX ? e.now_us() : t_us, value);
      return 0;
    });
}

void Line::scan_at(uint64_t t_us) {
  if (due_us_.size() != cells_.size()) throw Error("line " + name() + ": scan_at before run()");
  for (size_t i = 0; i < cells_.size(); ++i) scan_cell(i, t_us);
}

void Line::scan_cell(size_t i, uint64_t t_us) {
  // Due at t_us: a multiple of its period (found by stepping, not by a division a scan).
  uint64_t& due = due_us_[i];
  if (due < t_us) due += (t_us - due + periods_[i] - 1) / periods_[i] * periods_[i];
  if (due != t_us || !cells_[i]) return;
  due += periods_[i];
  if (!inbox_[i].empty()) take_inbox(i, t_us);
  WireTaps& taps = taps_[i];
  cells_[i]->plc().locked([&](ScanEngine& e, Memory& m) {
    e.scan(t_us);
    taps.sample(m, t_us);
    return 0;
  });
  if (!taps.pending().empty()) carry(i);
  if (after_scan_) after_scan_(i, t_us);
}

// Instant by instant, a sample reaches its sink right after its source's scan: before the
// sink's next scan, in the order of the instants and, at one instant, of the cells. A window
// taken cell by cell brings a source's samples before or after the sink's scans of the whole
// window; sorted back into that order and held until the same scan, the sink's wires see
// them exactly as they would have (the edges of an input X0-X15 share one queue with the
// cell's own, ties in time kept in the order they came).
void Line::take_inbox(size_t i, uint64_t t_us) {
  std::vector<Inbound>& box = inbox_[i];
  const auto before = [](const Inbound& a, const Inbound& b) {
    return a.t_us != b.t_us ? a.t_us < b.t_us : a.from_cell < b.from_cell;
  };
  if (!std::is_sorted(box.begin(), box.end(), before)) std::stable_sort(box.begin(), box.end(), before);
  const auto due = std::partition_point(box.begin(), box.end(), [&](const Inbound& x) {
    return x.t_us < t_us || (x.t_us == t_us && x.from_cell < i);
  });
  if (due == box.begin()) return;
  const auto each = [&](const std::vector<std::unique_ptr<WireSink>>& sinks, Plc& plc) {
    plc.locked([&](ScanEngine&, Memory&) {
      for (auto x = box.begin(); x != due; ++x) sinks[x->wire]->receive(x->t_us, x->value);
      return 0;
    });
  };
  each(sinks_, cells_[i]->plc());
  if (SoftCell* twin = cells_[i]->twin()) each(twin_sinks_, twin->plc());
  box.erase(box.begin(), due);
}

std::string Line::fault() {
  for (size_t i = 0; i < cells_.size(); ++i) {
    if (!cells_[i]) continue;
    const std::string f = cells_[i]->plc().locked([](ScanEngine& e, Memory&) { return e.fault(); });
    if (!f.empty()) return entry(i).name + ": " + f;
  }
  return "";
}

void Line::receive(size_t wire, uint32_t value) { receive(wire, UINT64_MAX, value); }

void Line::receive(size_t wire, uint64_t t_us, uint32_t value) {
  if (wire >= wires_.size() || sinks_.size() != wires_.size() || !sinks_[wire])
    throw Error("line " + name() + ": wire " + std::to_string(wire) + " has no sink in this process");
  deliver(wire, t_us, value);
}

void Line::start_real_time(unsigned shared_threads) {
  real_time_ = true;
  connect();
  for (size_t i = 0; i < size(); ++i) {
    if (!here(i)) continue;
    Cell& c = *cells_[i];
    // After each scan, on the scan's thread: the taps read in one memory copy, then carried.
    auto after = [this, i, &c] {
      const uint64_t t = c.plc().locked([&](ScanEngine& e, Memory& m) {
        taps_[i].sample(m, e.now_us());
        return e.now_us();
      });
      if (!taps_[i].pending().empty()) carry(i);
      if (after_scan_) after_scan_(i, t);
    };
    if (shared_threads == 0) {
      c.start_scanning(after);
    } else {
      SharedScanThread& t = SharedScanThread::process(shared_threads);
      shared_.push_back({&t, t.add(c.plc(), std::chrono::microseconds(periods_[i]), after, c.rt_priority())});
    }
  }
}

void Line::stop() {
  for (const auto& s : shared_) s.first->remove(s.second);
  shared_.clear();
  for (auto& c : cells_)
    if (c) c->stop();
}

}  // namespace line
}  // namespace plc_cell
