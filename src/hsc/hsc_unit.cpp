#include "plc_cell/hsc/hsc_unit.h"

#include <algorithm>
#include <cmath>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {
namespace hsc {

namespace {
ScanEngine& engine_of(Plc& p) { return *p.locked([](ScanEngine& e, Memory&) { return &e; }); }
Memory& memory_of(Plc& p) { return *p.locked([](ScanEngine&, Memory& m) { return &m; }); }
int counter_source(int n) { return n < 4 ? kHsc0I + n : kHsc4I + (n - 4); }
}  // namespace

HscUnit::HscUnit(Plc& plc, HscConfig cfg)
    : engine_(engine_of(plc)),
      mem_(memory_of(plc)),
      plc_(plc),
      sched_(*plc.locked([](ScanEngine& e, Memory&) { return &timeline::Scheduler::of(e); })),
      cfg_(std::move(cfg)) {
  pin_phase_.fill(-1);
  for (const auto& d : cfg_.sources) {
    sources_.push_back(std::make_unique<PulseSource>(d.name, d.pin_a, d.pin_b));
    PulseSource* s = sources_.back().get();
    s->set_rate(0, d.has_follow ? 0.0 : d.hz);
    bind_pins(s, d.pin_a, d.pin_b);
  }
  bind_counters();
  for (int n = 0; n < 8; ++n)
    if (counters_[n].def.used && !counters_[n].def.timer && n >= 4)
      irq().set_priority(counter_source(n), x_edge_source(counters_[n].def.pin_a, false) + 1);
  for (int x = 16; x < kFilteredInputs; ++x) scan_filter_[x - 16] = ScanDebounce(cfg_.filter_ns[x]);
  for (int x : cfg_.pulse.inputs) {
    meters_[x].on = true;
    meters_[x].m = PulseMeter(cfg_.pulse.timeout_ns);
  }
  for (const auto& e : cfg_.edges) schedule_edge(e.x, e.t_ns, e.level);
  plc_.locked([this](ScanEngine& e, Memory&) {
    e.add_hook(this);  // after the scheduler's: each scan finds the clock at the scan's instant
    sched_.add_source(this);
    return 0;
  });
}

HscUnit::~HscUnit() {
  plc_.locked([this](ScanEngine& e, Memory&) {
    sched_.remove_source(this);
    e.remove_hook(this);
    return 0;
  });
}

void HscUnit::bind_pins(EdgeSource* s, int pin_a, int pin_b) {
  for (int k = 0; k < 2; ++k) {
    const int x = k == 0 ? pin_a : pin_b;
    if (x < 0) continue;
    if (x > 15) throw Error(s->name() + ": X" + std::to_string(x) + " is not a high-speed input (X0-X15)");
    if (pin_src_[x]) throw Error("counters.sources: X" + std::to_string(x) + " is driven by both " +
                                 pin_src_[x]->name() + " and " + s->name());
    pin_src_[x] = s;
    pin_phase_[x] = k;
  }
}

// Which source drives each counter's counting inputs (again after attach_source).
void HscUnit::bind_counters() {
  for (int n = 0; n < 8; ++n) {
    Counter& c = counters_[n];
    c.n = n;
    c.def = cfg_.counters[n];
    c.src = nullptr;
    c.phase[0] = c.phase[1] = -1;
    if (!c.def.used || c.def.timer) continue;
    for (int k = 0; k < 2; ++k) {
      const int x = k == 0 ? c.def.pin_a : c.def.pin_b;
      if (x < 0 || !pin_src_[x]) continue;
      if (c.src && c.src != pin_src_[x])
        throw Error("HSC" + std::to_string(n) + ": its counting inputs are driven by two sources (" +
                    c.src->name() + ", " + pin_src_[x]->name() + "); give it one encoder");
      c.src = pin_src_[x];
      c.phase[k] = pin_phase_[x];
    }
    for (int x : {c.def.pin_mask, c.def.pin_clear})
      if (x >= 0 && pin_src_[x])
        throw Error("HSC" + std::to_string(n) + ": X" + std::to_string(x) +
                    " is a MASK/CLEAR input; pulse sources drive counting or interrupt inputs only");
    if (running() && c.src) take_quarter(c);
  }
}

void HscUnit::attach_source(EdgeSource* s, int pin_a, int pin_b) {
  // All or nothing: a source refused on its second pin, or by a counter it would share,
  // leaves no pin bound, so the unit stays consistent and detaching the others (when the
  // cell that refused it is torn down) cannot fail.
  try {
    bind_pins(s, pin_a, pin_b);
    bind_counters();
  } catch (...) {
    for (int x = 0; x < 16; ++x)
      if (pin_src_[x] == s) {
        pin_src_[x] = nullptr;
        pin_phase_[x] = -1;
      }
    bind_counters();
    throw;
  }
  for (int x : {pin_a, pin_b})
    if (x >= 0 && running()) cap_q_[x] = s->quarter(now());
}

void HscUnit::detach_source(EdgeSource* s) {
  for (int x = 0; x < 16; ++x)
    if (pin_src_[x] == s) {
      pin_src_[x] = nullptr;
      pin_phase_[x] = -1;
    }
  bind_counters();
}

HscUnit* HscUnit::of(ScanEngine* engine) { return engine ? engine->extensions().get<HscUnit>() : nullptr; }

void HscUnit::attached(ScanEngine& e) { e.extensions().attach(this); }
void HscUnit::detached(ScanEngine& e) { e.extensions().detach(this); }

// ---- levels and counting ------------------------------------------------------

bool HscUnit::term(int x, uint64_t t) const {
  if (pin_src_[x]) return !blocked(x) && pin_src_[x]->level(pin_phase_[x], pin_src_[x]->quarter(t));
  return term_[x];
}

// A source's pulses on x last half a period (50 % duty); shorter than the filter
// width they are all lost, and the filtered input stays OFF.
bool HscUnit::blocked(int x) const {
  const uint64_t w = cfg_.filter_ns[x];
  return pin_src_[x] && w > 0 && 2.0 * std::abs(pin_src_[x]->rate_hz()) * double(w) > 1e9;
}

bool HscUnit::blocked(const Counter& c) const {
  for (int k = 0; k < 2; ++k) {
    const int x = k == 0 ? c.def.pin_a : c.def.pin_b;
    if (c.phase[k] >= 0 && blocked(x)) return true;
  }
  return false;
}

bool HscUnit::cleared(const Counter& c) const {
  return (c.def.pin_clear >= 0 && term_[c.def.pin_clear] != c.def.inv_clear) || c.sw_clear;
}

bool HscUnit::counting(const Counter& c) const {
  if (!c.def.used || c.def.timer || cleared(c)) return false;
  if ((c.def.pin_mask >= 0 && term_[c.def.pin_mask] != c.def.inv_mask) || c.sw_mask) return false;
  if (c.n >= 4 && !irq().enabled(counter_source(c.n))) return false;  // a disabled SHSC stops counting
  return true;
}

Pins HscUnit::pins_at(const Counter& c, int64_t q) const {
  auto lvl = [&](int pin, int ph) { return ph >= 0 ? c.src->level(ph, q) : term_[pin]; };
  Pins p;
  p.a = lvl(c.def.pin_a, c.phase[0]) != c.def.inv_count;
  if (c.def.pin_b >= 0) p.b = lvl(c.def.pin_b, c.phase[1]) != c.def.inv_count;
  else if (c.def.mode == Mode::PR || c.def.mode == Mode::PRx2) p.b = c.sw_dir;
  return p;
}

// Only the enhanced decoder has a memory; it can lock out the first boundary alone
// (the source starts inside "both OFF", entered through the phase it now leaves by),
// so its weights are taken over two periods. Every other rule repeats from the first.
void HscUnit::weights(const Counter& c, std::array<int, 4>* first, std::array<int, 4>* seq) const {
  const int dir = c.src->direction();
  const int span = c.def.decoding == Decoding::Enhanced ? 8 : 4;
  DecodeState s = c.dec;
  for (int i = 1; i <= span; ++i) {
    const int64_t from = c.q + (i - 1) * dir, to = c.q + i * dir;
    (i <= 4 ? (*first)[i - 1] : (*seq)[i - 5]) =
        decode_delta(c.def.mode, c.def.decoding, &s, pins_at(c, from), pins_at(c, to));
  }
  if (span == 4) *seq = *first;
}

// The enhanced decoder's memory is the phase that changed last: after the first
// four boundaries it repeats every four, so k boundaries cost at most eight steps.
DecodeState HscUnit::decoder_after(const Counter& c, int64_t k) const {
  DecodeState s = c.dec;
  if (c.def.decoding != Decoding::Enhanced || k <= 0) return s;
  const int dir = c.src->direction();
  const int64_t steps = k <= 8 ? k : 4 + (k - 4) % 4;
  for (int64_t i = 1; i <= steps; ++i)
    decode_delta(c.def.mode, c.def.decoding, &s, pins_at(c, c.q + (i - 1) * dir), pins_at(c, c.q + i * dir));
  return s;
}

// The decoder sees every change of its inputs, counting or not (MASK and CLEAR stop
// the count, not the decoder).
int HscUnit::delta(Counter& c, Pins before, Pins after) {
  return decode_delta(c.def.mode, c.def.decoding, &c.dec, before, after);
}

uint32_t HscUnit::get_cv(const Counter& c) const {
  if (c.n < 4) return c.cv;
  const uint32_t r = cv_register(c.n);
  return uint32_t(mem_.reg(Area::R, r)) | (uint32_t(mem_.reg(Area::R, r + 1)) << 16);
}

uint32_t HscUnit::get_pv(const Counter& c) const {
  if (c.n < 4) return c.pv;
  const uint32_t r = pv_register(c.n);
  return uint32_t(mem_.reg(Area::R, r)) | (uint32_t(mem_.reg(Area::R, r + 1)) << 16);
}

void HscUnit::set_cv(Counter& c, uint32_t v) {
  if (c.n < 4) {
    c.cv = v;
    return;
  }
  mem_.set_reg(Area::R, cv_register(c.n), static_cast<uint16_t>(v));
  mem_.set_reg(Area::R, cv_register(c.n) + 1, static_cast<uint16_t>(v >> 16));
}

void HscUnit::add_count(Counter& c, int64_t d, bool check) {
  if (d == 0) return;
  const uint32_t v = get_cv(c) + static_cast<uint32_t>(d);
  set_cv(c, v);
  c.total += d;
  if (check && v == get_pv(c)) {
    sched_.raise(counter_source(c.n));
    for (auto& f : match_obs_) f(now(), c.n, c.def.timer);
  }
}

void HscUnit::take_quarter(Counter& c) {
  c.q = c.src->quarter(now());
  c.last = pins_at(c, c.q);
  c.epoch = c.src->epoch();
}

// The source changed at now() (a move started, was cut or ended): its levels
// before and after are one transition of the counting inputs. Counts are exact
// through a cut too, since an axis completes a pulse whose edge has left the pin
// (docs/motion.md "Pulse pins").
void HscUnit::resync(Counter& c) {
  const int64_t q = c.src->quarter(now());
  const Pins now = pins_at(c, q);
  const int d = delta(c, c.last, now);
  if (counting(c) && !blocked(c)) add_count(c, d, true);
  c.q = q;
  c.last = now;
  c.epoch = c.src->epoch();
}

void HscUnit::advance_counters(uint64_t t) {
  for (auto& c : counters_) {
    if (!c.src) continue;
    const int64_t q1 = c.src->quarter(t);
    if (q1 == c.q) continue;
    const int64_t k = q1 > c.q ? q1 - c.q : c.q - q1;
    if (counting(c) && !blocked(c)) {
      std::array<int, 4> first, seq;
      weights(c, &first, &seq);
      int64_t d = 0, n = 0;
      for (int i = 0; i < k && i < 4; ++i) d += first[i];
      if (k > 4) {
        for (int i = 0; i < 4; ++i) n += seq[i];
        d += ((k - 4) / 4) * n;
        for (int i = 0; i < (k - 4) % 4; ++i) d += seq[i];
      }
      add_count(c, d, false);  // matches inside the span are events of their own
    }
    c.dec = decoder_after(c, k);
    c.q = q1;
    c.last = pins_at(c, q1);
  }
}

// The edges of each measured analytic pin in (now, t]: the source is in one state
// over the span, so each boundary's instant is exact. Two cycles (8 quarters) hold the
// last full cycle, which is all a meter keeps; earlier boundaries are skipped.
void HscUnit::advance_meters(uint64_t t) {
  for (int x = 0; x < 16; ++x) {
    Meter& m = meters_[x];
    if (!m.on) continue;
    EdgeSource* s = pin_src_[x];
    if (s != m.src) {  // attached, detached, or the first step of a run
      m.src = s;
      if (s) {
        m.q = s->quarter(now());
        m.level = s->level(pin_phase_[x], m.q);
        m.epoch = s->epoch();
      }
    }
    if (!s) continue;
    const int64_t q1 = s->quarter(t);
    if (q1 == m.q) continue;
    const int64_t dir = q1 > m.q ? 1 : -1;
    const int64_t from = (q1 - m.q) * dir > 8 ? q1 - 8 * dir : m.q;
    const bool lost = blocked(x);  // a source faster than the filter leaves the input OFF
    for (int64_t q = from; q != q1; q += dir) {
      const bool a = s->level(pin_phase_[x], q), b = s->level(pin_phase_[x], q + dir);
      if (a != b && !lost) m.m.edge(s->time_of_quarter(q + dir, now()), b);
    }
    m.q = q1;
    m.level = s->level(pin_phase_[x], q1);
  }
}

// First instant after now at which counting makes CV equal PV: the k-th boundary
// the source crosses, solved in O(1) from the 4-periodic weights.
uint64_t HscUnit::next_match(const Counter& c) const {
  const int s = counter_source(c.n);
  if (!c.src || c.src->direction() == 0 || !irq().present(s) || !irq().enabled(s) || !counting(c) || blocked(c))
    return kNever;
  std::array<int, 4> first, seq;
  weights(c, &first, &seq);
  const int64_t to_pv = static_cast<int32_t>(get_pv(c) - get_cv(c));
  int64_t prefix = 0;
  for (int j = 1; j <= 4; ++j) {
    prefix += first[j - 1];
    if (first[j - 1] != 0 && prefix == to_pv) return c.src->time_of_quarter(c.q + j * c.src->direction(), now());
  }
  // Past the first four boundaries: the k-th of the repeating ones, k counted from the fifth.
  const int64_t target = to_pv - prefix;
  prefix = 0;
  int64_t n = 0;
  for (int i = 0; i < 4; ++i) n += seq[i];
  int64_t best = -1;
  for (int j = 1; j <= 4; ++j) {
    prefix += seq[j - 1];
    if (seq[j - 1] == 0) continue;  // CV changes only where an edge counts
    const int64_t d = target - prefix;
    int64_t k = -1;
    if (n == 0) {
      if (d == 0) k = j;
    } else if (d % n == 0 && d / n >= 0) {
      k = 4 * (d / n) + j;
    }
    if (k > 0 && (best < 0 || k < best)) best = k;
  }
  if (best < 0) return kNever;
  return c.src->time_of_quarter(c.q + (4 + best) * c.src->direction(), now());
}

// ---- timers ------------------------------------------------------------------

uint32_t HscUnit::hst_cv(const Counter& c, uint64_t t) const {
  return c.t_cv0 + static_cast<uint32_t>((t - c.t_base) / kTick);
}

uint64_t HscUnit::hst_match(const Counter& c) const {
  const int s = kHsc0I + c.n;
  if (!irq().present(s) || !irq().enabled(s)) return kNever;
  uint64_t ticks = static_cast<uint32_t>(c.pv - c.t_cv0);
  if (ticks == 0) ticks = 1ull << 32;
  uint64_t t = c.t_base + ticks * kTick;
  while (t <= now()) t += (1ull << 32) * kTick;
  return t;
}

uint64_t HscUnit::hsta_next() const {
  if (hsta_pv_ == 0 || !irq().present(kHstaI) || !irq().enabled(kHstaI)) return kNever;
  const uint64_t period = std::max<uint64_t>(hsta_pv_, 2) * kTick;  // PV = 1 acts as 2 (AMBIG-12)
  return hsta_t0_ + ((now() - hsta_t0_) / period + 1) * period;
}

int HscUnit::active_time_base() const {
  const uint16_t mask = mem_.reg(Area::R, kTimeBaseMask);
  for (int i = 0; i < 8; ++i)
    if (!((mask >> i) & 1) && irq().present(kTimeBase0 + i)) return i;  // the smallest unmasked
  return -1;
}

uint64_t HscUnit::next_pin_edge(int x, bool rising) const {
  const EdgeSource* s = pin_src_[x];
  const int dir = s->direction();
  if (dir == 0 || blocked(x)) return kNever;
  const int64_t q = s->quarter(now());
  for (int i = 1; i <= 4; ++i) {
    const bool a = s->level(pin_phase_[x], q + (i - 1) * dir), b = s->level(pin_phase_[x], q + i * dir);
    if (a != b && b == rising) return s->time_of_quarter(q + i * dir, now());
  }
  return kNever;
}

// ---- in the scheduler's loop -----------------------------------------------------

void HscUnit::start(uint64_t t) {
  run_ns_ = prev_ns_ = t;
  for (auto& c : counters_) {
    c.cv = c.pv = 0;
    c.sw_mask = c.sw_clear = c.sw_dir = false;
    c.total = 0;
    c.hist.clear();
    c.t_cv0 = 0;
    c.t_base = t;
    c.dec = DecodeState{};
    if (c.src) take_quarter(c);
  }
  hsta_pv_ = 0;
  hsta_cv0_ = 0;
  hsta_t0_ = t;
  for (int x = 0; x < 16; ++x) {
    if (!pin_src_[x]) term_[x] = raw_[x] = engine_.input(x);
    else cap_q_[x] = pin_src_[x]->quarter(t);
    ++gen_[x];  // filter outputs pending from the last run are void
    latch_[x] = false;
    Meter& m = meters_[x];
    m.m.reset();
    m.src = nullptr;  // taken again at the first step
  }
  for (auto& f : scan_filter_) f.reset();
}

void HscUnit::stop() { refresh_outputs(0, 256); }

void HscUnit::settle() {
  for (auto& c : counters_)
    if (c.src && c.src->epoch() != c.epoch) resync(c);
  // A source's jump is one edge of a measured pin if its level changed.
  for (int x = 0; x < 16; ++x) {
    Meter& m = meters_[x];
    if (!m.on || !m.src || m.src != pin_src_[x] || m.src->epoch() == m.epoch) continue;
    m.q = m.src->quarter(now());
    const bool level = m.src->level(pin_phase_[x], m.q);
    if (level != m.level && !blocked(x)) m.m.edge(now(), level);
    m.level = level;
    m.epoch = m.src->epoch();
  }
}

uint64_t HscUnit::next_event_ns() {
  uint64_t t = kNever;
  for (auto& c : counters_) {
    match_[c.n] = !c.def.used ? kNever : c.def.timer ? hst_match(c) : next_match(c);
    t = std::min(t, match_[c.n]);
  }
  hsta_next_ = hsta_next();
  t = std::min(t, hsta_next_);
  tb_ = active_time_base();
  tb_next_ = kNever;
  if (tb_ >= 0) {
    const uint64_t p = uint64_t(kTimeBaseMs[tb_]) * 1000000;
    tb_next_ = run_ns_ + ((now() - run_ns_) / p + 1) * p;
    t = std::min(t, tb_next_);
  }
  pin_edge_.fill(kNever);
  for (int e : cfg_.edge_interrupts) {
    const int x = e / 2;
    if (!pin_src_[x] || !irq().present(kX0Up + e) || !irq().enabled(kX0Up + e)) continue;
    pin_edge_[e] = next_pin_edge(x, e % 2 == 0);
    t = std::min(t, pin_edge_[e]);
  }
  if (!edges_.empty()) t = std::min(t, std::max(edges_.top().t, now()));
  for (const auto& tr : trains_) {
    bool up;
    if (!muted_[tr.x]) t = std::min(t, tr.next_after(now(), &up));
  }
  return t;
}

void HscUnit::advance_to(uint64_t t) {
  advance_counters(t);
  advance_meters(t);
  prev_ns_ = now();
}

void HscUnit::at(uint64_t t) {
  for (auto& c : counters_)
    if (match_[c.n] == t) {
      sched_.raise(counter_source(c.n));
      for (auto& f : match_obs_) f(t, c.n, c.def.timer);
    }
  if (hsta_next_ == t) sched_.raise(kHstaI);
  if (tb_next_ == t) sched_.raise(kTimeBase0 + tb_);
  for (int e = 0; e < 32; ++e)
    if (pin_edge_[e] == t) sched_.raise(kX0Up + e);
  std::vector<std::pair<int, bool>> group;
  for (const auto& tr : trains_) {
    bool up;
    if (!muted_[tr.x] && tr.next_after(prev_ns_, &up) == t) group.push_back({tr.x, up});
  }
  while (!edges_.empty() && edges_.top().t <= t) {
    const Edge e = edges_.top();
    edges_.pop();
    if (e.simulated) {
      sim_raw_[e.x] = e.level;
      if (muted_[e.x]) continue;
    }
    raw_edge(e, &group);
  }
  if (group.empty()) return;
  // Edges at one instant act together: simultaneous U and D edges cancel.
  std::array<Pins, 8> before;
  for (auto& c : counters_)
    if (c.def.used && !c.def.timer) before[c.n] = pins_at(c, c.q);
  std::array<bool, 16> old = term_;
  for (const auto& g : group)
    if (!pin_src_[g.first]) term_[g.first] = raw_[g.first] = g.second;
  std::array<bool, 16> level = term_;
  for (auto& c : counters_) {
    if (!c.def.used || c.def.timer) continue;
    term_ = old;
    const bool was_counting = counting(c);
    term_ = level;
    const int d = delta(c, before[c.n], pins_at(c, c.q));
    if (was_counting && counting(c)) add_count(c, d, true);
    if (cleared(c)) set_cv(c, 0);
  }
  for (int x = 0; x < 16; ++x) {
    if (old[x] == level[x]) continue;
    engine_.set_input(x, level[x]);
    if (level[x]) latch_[x] = true;
    if (meters_[x].on) meters_[x].m.edge(t, level[x]);
    // An input edge interrupts only if configured with a routine (manual §9.5).
    const int e = 2 * x + (level[x] ? 0 : 1);
    if (std::find(cfg_.edge_interrupts.begin(), cfg_.edge_interrupts.end(), e) != cfg_.edge_interrupts.end())
      sched_.raise(x_edge_source(x, !level[x]));
  }
}

// An edge at the terminal. Unfiltered it acts now; filtered, it acts once the
// level has held for the filter width (a debounce: shorter pulses are lost, longer
// ones arrive that much late), unless the terminal changes back before.
void HscUnit::raw_edge(const Edge& e, std::vector<std::pair<int, bool>>* group) {
  const uint64_t w = cfg_.filter_ns[e.x];
  if (e.commit) {
    if (e.gen == gen_[e.x]) group->push_back({e.x, e.level});
    return;
  }
  if (w == 0 || pin_src_[e.x]) {
    group->push_back({e.x, e.level});
    return;
  }
  if (e.level == raw_[e.x]) return;
  raw_[e.x] = e.level;
  engine_.set_input(e.x, e.level);
  ++gen_[e.x];
  if (e.level != term_[e.x]) edges_.push({e.t + w, edge_seq_++, e.x, e.level, true, gen_[e.x]});
}

void HscUnit::schedule_edge(int x, uint64_t t_ns, bool level) {
  if (x >= 0 && x < 16) simulated_[x] = true;
  Edge e{t_ns, edge_seq_++, x, level};
  e.simulated = true;
  edges_.push(e);
}

void HscUnit::mute_simulation(int x, bool muted) {
  if (x < 0 || x > 15 || muted_[x] == muted) return;
  muted_[x] = muted;
  if (muted || !simulated_[x]) return;
  engine_.set_input(x, raw_[x]);  // not yet scanned: the simulation's level comes instead
  const auto train = std::find_if(trains_.begin(), trains_.end(), [x](const Train& t) { return t.x == x; });
  if (train == trains_.end()) {
    edges_.push({now(), edge_seq_++, x, sim_raw_[x]});  // through the filter, as the steps' edges
    return;
  }
  // A train's levels are the filter's output already: they act unfiltered, and whatever
  // the filter still holds from outside is void.
  ++gen_[x];
  edges_.push({now(), edge_seq_++, x, train->level_at(now()), true, gen_[x]});
}

void HscUnit::add_pulse_train(int x, uint64_t period_ns, uint64_t width_ns, uint64_t delay_ns) {
  if (x < 0 || x > 15 || pin_src_[x]) throw Error("X" + std::to_string(x) + ": no pulse train here");
  simulated_[x] = true;
  if (period_ns == 0 || width_ns == 0) return;  // never on
  if (width_ns >= period_ns) {
    schedule_edge(x, delay_ns, true);  // on for good
    return;
  }
  // The filter, in O(1) for the whole train: it loses ON pulses shorter than its
  // width, bridges OFF gaps shorter than it, and delays the rest by its width.
  const uint64_t w = cfg_.filter_ns[x];
  if (w > 0) {
    if (width_ns < w) return;
    if (period_ns - width_ns < w) {
      schedule_edge(x, delay_ns, true);  // on for good, once the filter has seen it
      return;
    }
    delay_ns += w;
  }
  trains_.push_back({x, period_ns, width_ns, delay_ns});
}

// First edge strictly after t: rising at delay + k*period, falling width later.
uint64_t HscUnit::Train::next_after(uint64_t t, bool* rising) const {
  if (t < delay) {
    *rising = true;
    return delay;
  }
  const uint64_t k = (t - delay) / period;
  const uint64_t r = delay + k * period;
  if (r + width > t) {
    *rising = false;
    return r + width;
  }
  *rising = true;
  return r + period;
}

// ---- scan hooks ------------------------------------------------------------------

void HscUnit::before_inputs(uint64_t) {
  if (!running()) return;  // the scheduler's hook, before this one, has brought the clock to now
  // Levels that the simulation or a ROS topic set since the last scan change now.
  for (int x = 0; x < 16; ++x)
    if (!pin_src_[x] && engine_.input(x) != raw_[x]) edges_.push({now(), edge_seq_++, x, engine_.input(x)});
  if (!edges_.empty() && edges_.top().t <= now()) sched_.advance(now());
  if (!running()) return;
  for (int x = 0; x < 16; ++x)
    if (pin_src_[x]) engine_.set_input(x, term(x, now()));
  for (auto& c : counters_) {
    if (!c.def.used || c.def.timer) continue;
    c.hist.push_back({now(), c.total});
    const uint64_t w = cfg_.frequency_window_us * 1000;
    while (c.hist.size() > 2 && c.hist[1].first + w <= now()) c.hist.pop_front();
  }
}

// After the input image is taken: the filtered levels of X0-X15, the capture
// latches (ON at some instant since the last image) and the scan filter of X16-X35.
void HscUnit::before_program(uint64_t now_us) {
  if (!running()) return;
  for (int x = 0; x < 16; ++x) {
    bool on = false;
    if (pin_src_[x]) {
      if (cfg_.capture[x]) on = source_was_on(x);
      cap_q_[x] = pin_src_[x]->quarter(now());
    } else {
      if (cfg_.filter_ns[x] > 0) mem_.set_bit(Area::X, x, term_[x]);  // the terminal shows the raw level
      on = latch_[x] && cfg_.capture[x];
      latch_[x] = term_[x];  // ON now: ON just after this image, too
    }
    if (on) mem_.set_bit(Area::X, x, true);
  }
  for (int x = 16; x < kFilteredInputs; ++x)
    if (cfg_.filter_ns[x] > 0) mem_.set_bit(Area::X, x, scan_filter_[x - 16].sample(mem_.bit(Area::X, x), now_us * 1000));
}

// Some quarter between the last image and now put x ON (a pulse phase is ON in 2
// of any 4 consecutive quarters, so 3 quarters always contain one).
bool HscUnit::source_was_on(int x) const {
  if (blocked(x)) return false;
  const int64_t q1 = pin_src_[x]->quarter(now());
  const int64_t lo = std::min(cap_q_[x], q1), hi = std::max(cap_q_[x], q1);
  if (hi - lo >= 3) return true;
  for (int64_t q = lo; q <= hi; ++q)
    if (pin_src_[x]->level(pin_phase_[x], q)) return true;
  return false;
}

void HscUnit::after_program(uint64_t) {
  if (!running()) return;
  // The software MASK/CLEAR/direction relays reach the counters at the I/O refresh.
  for (auto& c : counters_) {
    if (!c.def.used || c.def.timer) continue;
    c.sw_mask = mem_.bit(Area::M, mask_relay(c.n));
    c.sw_clear = clear_relay(c.n) >= 0 && mem_.bit(Area::M, clear_relay(c.n));
    c.sw_dir = mem_.bit(Area::M, dir_relay(c.n));
    if (cleared(c)) set_cv(c, 0);
  }
  refresh_outputs(0, 256);
}

void HscUnit::refresh_outputs(uint32_t first, uint32_t n) {
  for (uint32_t y = first; y < first + n && y < phys_y_.size(); ++y) {
    if (owned_y_[y]) continue;
    const bool v = mem_.bit(Area::Y, y);
    if (v == phys_y_[y]) continue;
    phys_y_[y] = v;
    for (auto& f : output_obs_) f(now(), y, v);
    for (size_t i = 0; i < cfg_.sources.size(); ++i) {
      const SourceDef& d = cfg_.sources[i];
      if (d.has_follow && d.follow.area == Area::Y && d.follow.index == y) sources_[i]->set_rate(now(), v ? d.hz : 0);
    }
  }
}

// ---- instructions ------------------------------------------------------------------

void HscUnit::read_chip(int cn) {
  if (cn == 4) {
    const uint64_t ticks = (now() - hsta_t0_) / kTick;
    const uint32_t v = hsta_pv_ == 0 ? hsta_cv0_ + static_cast<uint32_t>(ticks)
                                     : static_cast<uint32_t>(ticks % std::max<uint64_t>(hsta_pv_, 2));
    mem_.set_reg(Area::R, kHstaCv, static_cast<uint16_t>(v));
    mem_.set_reg(Area::R, kHstaCv + 1, static_cast<uint16_t>(v >> 16));
    return;
  }
  if (cn < 0 || cn > 3) return;
  const Counter& c = counters_[cn];
  const uint32_t v = c.def.timer ? hst_cv(c, now()) : c.cv;
  mem_.set_reg(Area::R, cv_register(cn), static_cast<uint16_t>(v));
  mem_.set_reg(Area::R, cv_register(cn) + 1, static_cast<uint16_t>(v >> 16));
}

void HscUnit::write_chip(int cn, bool pv) {
  auto reg32 = [&](uint32_t r) { return uint32_t(mem_.reg(Area::R, r)) | (uint32_t(mem_.reg(Area::R, r + 1)) << 16); };
  if (cn == 4) {
    if (pv) hsta_pv_ = mem_.reg(Area::R, kHstaPv);
    else hsta_cv0_ = reg32(kHstaCv);
    hsta_t0_ = now();  // the timer starts over from the write
    return;
  }
  if (cn < 0 || cn > 3) return;
  Counter& c = counters_[cn];
  if (pv) {
    c.pv = reg32(pv_register(cn));
  } else if (c.def.timer) {
    c.t_cv0 = reg32(cv_register(cn));
    c.t_base = now();
  } else {
    c.cv = reg32(cv_register(cn));
  }
}

bool HscUnit::set_enabled(const std::string& label, bool on) {
  const int s = source_of_label(label);
  if (s < 0) return false;
  irq().set_enabled(s, on);
  return true;
}

void HscUnit::immediate_io(const Address& first, uint32_t n) {
  if (first.area == Area::Y) {
    refresh_outputs(first.index, n);
  } else if (first.area == Area::X) {
    for (uint32_t x = first.index; x < first.index + n && x < 256; ++x)
      mem_.set_bit(Area::X, x, x < 16 ? term(static_cast<int>(x), now()) : engine_.input(x));
  }
}

// ---- observation ----------------------------------------------------------------------

PulseSource* HscUnit::source(const std::string& name) {
  for (auto& s : sources_)
    if (s->name() == name) return s.get();
  return nullptr;
}

void HscUnit::set_source_rate(const std::string& name, double hz) {
  PulseSource* s = source(name);
  if (!s) throw Error("no pulse source named '" + name + "'");
  for (auto& c : counters_)
    if (c.src == s) take_quarter(c);
  s->set_rate(now(), hz);
}

void HscUnit::preset(int n, int64_t value) {
  Counter& c = counters_[n];
  if (c.def.timer) {
    c.t_cv0 = static_cast<uint32_t>(value);
    c.t_base = now();
  } else {
    set_cv(c, static_cast<uint32_t>(value));
  }
}

int64_t HscUnit::count(int n) const {
  const Counter& c = counters_[n];
  if (c.def.timer) return hst_cv(c, now());
  return static_cast<int32_t>(get_cv(c));
}

PulseReading HscUnit::pulse(int x) const {
  if (x < 0 || x > 15 || !meters_[x].on) return {};
  return meters_[x].m.read(now());
}

double HscUnit::frequency(int n) const {
  const Counter& c = counters_[n];
  if (c.hist.size() < 2 || c.hist.back().first == c.hist.front().first) return 0.0;
  return double(c.hist.back().second - c.hist.front().second) * 1e9 /
         double(c.hist.back().first - c.hist.front().first);
}

}  // namespace hsc
}  // namespace plc_cell
