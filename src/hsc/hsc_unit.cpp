#include "plc_cell/hsc/hsc_unit.h"

#include <algorithm>

#include "plc_cell/core/error.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {
namespace hsc {

namespace {
ScanEngine& engine_of(Plc& p) { return *p.locked([](ScanEngine& e, Memory&) { return &e; }); }
Memory& memory_of(Plc& p) { return *p.locked([](ScanEngine&, Memory& m) { return &m; }); }
timeline::Scheduler& scheduler_of(Plc& p) {
  return *p.locked([](ScanEngine& e, Memory&) { return &timeline::Scheduler::of(e); });
}
}  // namespace

HscUnit::HscUnit(Plc& plc, HscConfig cfg)
    : plc_(plc),
      ctx_{engine_of(plc), memory_of(plc), scheduler_of(plc), {}},
      cfg_(std::move(cfg)),
      pins_(cfg_),
      terminal_(ctx_, pins_),
      outputs_(ctx_.mem),
      hsta_(ctx_),
      time_base_(ctx_),
      edge_irq_(ctx_, pins_, cfg_.edge_interrupts) {
  for (const auto& d : cfg_.sources) {
    sources_.push_back(std::make_unique<PulseSource>(d.name, d.pin_a, d.pin_b));
    PulseSource* s = sources_.back().get();
    s->set_rate(0, d.has_follow ? 0.0 : d.hz);
    if (d.has_follow && d.follow.area == Area::Y) outputs_.follow(d.follow.index, s, d.hz);
    pins_.bind(s, d.pin_a, d.pin_b);
  }
  compose();
  bind_counters();
  for (int n = 4; n < 8; ++n)
    if (cfg_.counters[n].used)
      ctx_.irq().set_priority(counter_source(n), x_edge_source(cfg_.counters[n].pin_a, false) + 1);
  for (int x = 16; x < kFilteredInputs; ++x)
    if (cfg_.filter_ns[x] > 0) scan_filters_.push_back({x, ScanDebounce(cfg_.filter_ns[x])});
  for (const auto& e : cfg_.edges) schedule_edge(e.x, e.t_ns, e.level);
  plc_.locked([this](ScanEngine& e, Memory&) {
    e.add_hook(this);  // after the scheduler's: each scan finds the clock at the scan's instant
    // The scheduler calls settle and advance_to only if some part of this unit has them
    // (the parts are composed once, above).
    ctx_.sched.add_source(this, (settling_.empty() ? 0u : timeline::EventSource::kSettles) |
                                    (advancing_.empty() ? 0u : timeline::EventSource::kAdvances));
    return 0;
  });
}

HscUnit::~HscUnit() {
  plc_.locked([this](ScanEngine& e, Memory&) {
    ctx_.sched.remove_source(this);
    e.remove_hook(this);
    return 0;
  });
}

// The parts in the order they act at one instant: the counters and timers by number
// (their interrupt requests and match observers in that order), the timer interrupts,
// the edge interrupts, the pulse measurements, the explicit edges.
void HscUnit::compose() {
  counters_.reserve(8);
  timers_.reserve(4);
  for (int n = 0; n < 8; ++n) counters_.emplace_back(ctx_, pins_, n, cfg_.counters[n], cfg_.frequency_window_us);
  for (int n = 0; n < 4; ++n) timers_.emplace_back(ctx_, n);
  meter_of_.fill(-1);
  meters_.reserve(cfg_.pulse.inputs.size());
  for (int x : cfg_.pulse.inputs) {
    meter_of_[x] = static_cast<int>(meters_.size());
    meters_.emplace_back(ctx_, pins_, x, cfg_.pulse.timeout_ns);
  }
  for (int n = 0; n < 8; ++n) {
    const CounterDef& d = cfg_.counters[n];
    if (!d.used) continue;
    if (d.timer) {
      add_part(&timers_[n]);
    } else {
      add_part(&counters_[n]);
      scanned_.push_back(&counters_[n]);
    }
  }
  add_part(&hsta_, uint64_t(1) << irq::kHstaI);
  add_part(&time_base_, uint64_t(0xFF) << irq::kTimeBase0);  // 1MSI ... 100MSI
  if (!cfg_.edge_interrupts.empty()) add_part(&edge_irq_);
  for (auto& m : meters_) add_part(&m);
  add_part(&terminal_);
}

// Which source drives each counter's counting inputs (again after attach_source).
void HscUnit::bind_counters() {
  for (auto& c : counters_) c.bind();
}

void HscUnit::attach_source(EdgeSource* s, int pin_a, int pin_b) {
  // All or nothing: a source refused on its second pin, or by a counter it would share,
  // leaves no pin bound, so the unit stays consistent and detaching the others (when the
  // cell that refused it is torn down) cannot fail.
  try {
    pins_.bind(s, pin_a, pin_b);
    bind_counters();
  } catch (...) {
    pins_.unbind(s);
    bind_counters();
    throw;
  }
  for (int x : {pin_a, pin_b})
    if (x >= 0 && running()) pins_[x].cap_q = s->quarter(now());
}

void HscUnit::detach_source(EdgeSource* s) {
  pins_.unbind(s);
  bind_counters();
}

HscUnit* HscUnit::of(ScanEngine* engine) { return engine ? engine->extensions().get<HscUnit>() : nullptr; }

void HscUnit::attached(ScanEngine& e) { e.extensions().attach(this); }
void HscUnit::detached(ScanEngine& e) { e.extensions().detach(this); }

// ---- in the scheduler's loop -----------------------------------------------------

void HscUnit::start(uint64_t t) {
  // Every counter and timer starts over, configured or not: FUN92/93 reach them all.
  for (auto& c : counters_) c.start(t);
  for (auto& h : timers_) h.start(t);
  hsta_.start(t);
  time_base_.start(t);
  for (auto& m : meters_) m.start(t);
  terminal_.start(t);
  pins_.start(t, ctx_.engine);
  for (auto& f : scan_filters_) f.second.reset();
}

void HscUnit::stop() { outputs_.refresh_all(now()); }

void HscUnit::settle() {
  for (Component* p : settling_) p->settle();
}

uint64_t HscUnit::next_event_ns() {
  const uint64_t routines = ctx_.irq().present_mask();
  if (routines != timed_for_) {
    timed_.clear();
    for (size_t i = 0; i < parts_.size(); ++i)
      if (routines_of_[i] == 0 || (routines_of_[i] & routines) != 0) timed_.push_back(parts_[i]);
    timed_for_ = routines;
  }
  uint64_t t = kNever;
  for (Component* p : timed_) t = std::min(t, p->next_event_ns());
  return t;
}

void HscUnit::advance_to(uint64_t t) {
  for (Component* p : advancing_) p->advance_to(t);
}

void HscUnit::at(uint64_t t) {
  // The parts asked for their next instant just before (the scheduler's loop): a part left
  // out there has nothing at t, and what it kept from an earlier program is void.
  for (Component* p : timed_) p->at(t);
  const std::vector<std::pair<int, bool>> group = terminal_.take(t);
  if (!group.empty()) act(t, group);
}

// Edges at one instant act together: simultaneous U and D edges cancel.
void HscUnit::act(uint64_t t, const std::vector<std::pair<int, bool>>& group) {
  const InputLevels before = pins_.levels();
  for (const auto& g : group)
    if (!pins_.driven(g.first)) {
      pins_.levels()[g.first] = g.second;
      pins_.set_raw(g.first, g.second);
    }
  const InputLevels after = pins_.levels();
  for (Component* p : parts_) p->input_edges(t, before, after);
  for (int x = 0; x < 16; ++x) {
    if (before[x] == after[x]) continue;
    ctx_.engine.set_input(x, after[x]);
    if (after[x]) pins_[x].latch = true;
  }
}

void HscUnit::schedule_edge(int x, uint64_t t_ns, bool level) { terminal_.schedule(x, t_ns, level); }
void HscUnit::mute_simulation(int x, bool muted) { terminal_.mute(x, muted); }
void HscUnit::add_pulse_train(int x, uint64_t period_ns, uint64_t width_ns, uint64_t delay_ns) {
  terminal_.add_train(x, period_ns, width_ns, delay_ns);
}

// ---- scan hooks ------------------------------------------------------------------

void HscUnit::before_inputs(uint64_t) {
  if (!running()) return;  // the scheduler's hook, before this one, has brought the clock to now
  // Levels that the simulation or a ROS topic set since the last scan change now.
  const uint8_t* const terminals = ctx_.engine.inputs();
  for (uint16_t c = pins_.undriven_changes(terminals); c != 0; c = static_cast<uint16_t>(c & (c - 1))) {
    const int x = __builtin_ctz(c);
    terminal_.external(x, terminals[x] != 0);
  }
  if (terminal_.due(now())) ctx_.sched.advance(now());
  if (!running()) return;
  for (uint16_t d = pins_.driven_mask(); d != 0; d = static_cast<uint16_t>(d & (d - 1))) {
    const int x = __builtin_ctz(d);
    ctx_.engine.set_input(x, pins_.level(x, now()));
  }
  for (Component* p : scanned_) p->before_inputs();
}

// After the input image is taken: the filtered levels of X0-X15, the capture
// latches (ON at some instant since the last image) and the scan filter of X16-X35.
void HscUnit::before_program(uint64_t now_us) {
  if (!running()) return;
  pins_.image(now(), ctx_.mem);
  for (auto& f : scan_filters_)
    ctx_.mem.set_bit(Area::X, f.first, f.second.sample(ctx_.mem.bit(Area::X, f.first), now_us * 1000));
}

void HscUnit::after_program(uint64_t) {
  if (!running()) return;
  for (Component* p : scanned_) p->after_program();
  outputs_.refresh_all(now());
}

// ---- instructions ------------------------------------------------------------------

void HscUnit::read_chip(int cn) {
  if (cn == 4) hsta_.read_chip();
  else if (cn >= 0 && cn <= 3) cfg_.counters[cn].timer ? timers_[cn].read_chip() : counters_[cn].read_chip();
}

void HscUnit::write_chip(int cn, bool pv) {
  if (cn == 4) hsta_.write_chip(pv);
  else if (cn >= 0 && cn <= 3) cfg_.counters[cn].timer ? timers_[cn].write_chip(pv) : counters_[cn].write_chip(pv);
}

bool HscUnit::set_enabled(const std::string& label, bool on) {
  const int s = source_of_label(label);
  if (s < 0) return false;
  ctx_.irq().set_enabled(s, on);
  return true;
}

void HscUnit::immediate_io(const Address& first, uint32_t n) {
  if (first.area == Area::Y) {
    outputs_.refresh(first.index, n, now());
  } else if (first.area == Area::X) {
    for (uint32_t x = first.index; x < first.index + n && x < 256; ++x)
      ctx_.mem.set_bit(Area::X, x, x < 16 ? pins_.level(static_cast<int>(x), now()) : ctx_.engine.input(x));
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
    if (c.source() == s) c.take_quarter();
  s->set_rate(now(), hz);
}

void HscUnit::preset(int n, int64_t value) {
  if (cfg_.counters[n].timer) timers_[n].preset(static_cast<uint32_t>(value));
  else counters_[n].set_cv(static_cast<uint32_t>(value));
}

int64_t HscUnit::count(int n) const {
  if (cfg_.counters[n].timer) return timers_[n].cv(now());
  return static_cast<int32_t>(counters_[n].cv());
}

PulseReading HscUnit::pulse(int x) const {
  if (x < 0 || x > 15 || meter_of_[x] < 0) return {};
  return meters_[meter_of_[x]].read();
}

double HscUnit::frequency(int n) const { return counters_[n].frequency(); }

}  // namespace hsc
}  // namespace plc_cell
