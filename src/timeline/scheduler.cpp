#include "plc_cell/timeline/scheduler.h"

#include <algorithm>

#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace timeline {

Scheduler& Scheduler::of(ScanEngine& engine) {
  // Owned by the engine's slots: it lives as long as the engine, so a subsystem that
  // goes (and removes its source) never leaves the others without a clock.
  Scheduler& s = engine.extensions().owned<Scheduler>();
  if (!s.engine_) {
    s.engine_ = &engine;
    engine.add_hook(&s);
  }
  return s;
}

Scheduler* Scheduler::find(ScanEngine* engine) {
  if (!engine) return nullptr;
  Scheduler* s = engine->extensions().get<Scheduler>();
  return s && s->engine_ ? s : nullptr;
}

void Scheduler::add_source(EventSource* s, unsigned steps) {
  sources_.push_back(s);
  if (steps & EventSource::kSettles) settling_.push_back(s);
  if (steps & EventSource::kAdvances) advancing_.push_back(s);
  if (running_) s->start(now_ns_);
}

void Scheduler::remove_source(EventSource* s) {
  for (auto* list : {&sources_, &settling_, &advancing_}) list->erase(std::remove(list->begin(), list->end(), s), list->end());
}

void Scheduler::start(uint64_t t) {
  now_ns_ = t;
  for (int s = 0; s < kSourceCount; ++s) irq_.set_enabled(s, true);
  irq_.reset();
  requested_.clear();
  running_ = true;
  for (EventSource* s : sources_) s->start(t);
}

void Scheduler::advance(uint64_t to) {
  while (running_) {
    in_instant_ = true;
    for (EventSource* s : settling_) s->settle();
    in_instant_ = false;
    if (!requested_.empty()) {  // e.g. a CV=PV reached by a source's jump interrupts at its instant
      dispatch();
      if (!running_) return;
    }
    uint64_t due = EventSource::kNever;
    for (EventSource* s : sources_) due = std::min(due, std::max(s->next_event_ns(), now_ns_));
    const uint64_t t = std::min(to, due);
    for (EventSource* s : advancing_) s->advance_to(t);
    now_ns_ = t;
    // Most scans fall between events: at `to` no source has anything to do (EventSource::at)
    // and no request waits (dispatch drains them all), so the instant ends here.
    if (due > t) return;
    in_instant_ = true;
    for (EventSource* s : sources_) s->at(t);
    in_instant_ = false;
    dispatch();
    if (t >= to) return;
  }
}

void Scheduler::raise(int source) {
  if (in_instant_) {
    requested_.push_back(source);
    return;
  }
  irq_.raise(source, [this](int s, const std::string&) { return run_isr(s); });
}

void Scheduler::dispatch() {
  // All requests of one instant are pending before any routine runs, so the highest
  // priority goes first whatever order the sources acted in.
  for (int s : requested_) irq_.request(s);
  requested_.clear();
  irq_.dispatch([this](int s, const std::string&) { return run_isr(s); });
}

bool Scheduler::run_isr(int source) {
  for (auto& f : isr_obs_) f(now_ns_, source);
  const std::string label = irq_.label(source);
  std::string why;
  if (engine_->run_routine(label, now_ns_ / 1000, &why)) return true;
  engine_->stop_with_fault("interrupt " + label + ": " + why);
  return false;
}

void Scheduler::before_inputs(uint64_t now_us) {
  if (engine_->mode() != RunMode::Run) {
    running_ = false;
    return;
  }
  const Program& prog = engine_->program();
  if (prog.code.data() != bound_code_ || prog.code.size() != bound_size_) {
    irq_.bind(prog);
    bound_code_ = prog.code.data();
    bound_size_ = prog.code.size();
  }
  const uint64_t now = now_us * 1000;
  if (!running_) start(now);
  if (now > now_ns_) advance(now);
}

void Scheduler::on_stop() {
  if (!running_) return;
  running_ = false;
  for (EventSource* s : sources_) s->stop();
}

}  // namespace timeline
}  // namespace plc_cell
