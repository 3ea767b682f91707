#include "plc_cell/sim/virtual_run.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/hsc/hsc_unit.h"
#include "plc_cell/timeline/scheduler.h"
#include "plc_cell/motion/motion_unit.h"

namespace plc_cell {

int value_bits(const Address& a) {
  if (is_discrete(a.area)) return a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  return a.width == Width::DWord ? 32 : 16;
}

std::pair<std::string, ValueFormat> split_format(const std::string& w) {
  const auto colon = w.rfind(':');
  if (colon == std::string::npos) return {w, ValueFormat::Default};
  const std::string f = w.substr(colon + 1), a = w.substr(0, colon);
  if (f == "s") return {a, ValueFormat::Signed};
  if (f == "u") return {a, ValueFormat::Unsigned};
  if (f == "hex") return {a, ValueFormat::Hex};
  if (f == "f32") return {a, ValueFormat::F32};
  throw Error(w + ": unknown format '" + f + "' (s, u, hex, f32)");
}

void check_format(const Address& a, ValueFormat f, const std::string& text) {
  if (f == ValueFormat::F32 && value_bits(a) != 32)
    throw Error(text + ": f32 needs a 32-bit address (DR, DD, DRC200...)");
  if (value_bits(a) == 1 && (f == ValueFormat::Signed || f == ValueFormat::F32))
    throw Error(text + ": a single bit has no sign");
}

std::string format_value(const Address& a, uint32_t v, ValueFormat f) {
  const int bits = value_bits(a);
  if (f == ValueFormat::Default) f = is_discrete(a.area) ? ValueFormat::Unsigned : ValueFormat::Signed;
  char buf[48];
  switch (f) {
    case ValueFormat::Unsigned:
      return std::to_string(v);
    case ValueFormat::Hex:
      std::snprintf(buf, sizeof buf, "0x%0*X", bits <= 1 ? 1 : bits / 4, v);
      return buf;
    case ValueFormat::F32: {
      float x;
      std::memcpy(&x, &v, sizeof x);
      std::snprintf(buf, sizeof buf, "%.9g", double(x));  // enough digits to give the float back
      return buf;
    }
    default:
      if (bits == 16) return std::to_string(int(int16_t(uint16_t(v))));
      if (bits == 32) return std::to_string(int64_t(int32_t(v)));
      return std::to_string(v);
  }
}

size_t VirtualRun::watch(const Address& a) {
  watches_.push_back(a);
  last_.push_back(0);
  seen_.push_back(false);
  return watches_.size() - 1;
}

void VirtualRun::trace_events() {
  auto ev = events_;
  plc_.locked([&](ScanEngine& e, Memory&) {
    if (timeline::Scheduler* sched = timeline::Scheduler::find(&e)) {
      sched->on_isr([ev](uint64_t t, int s) {
        const auto labels = irq::source_labels(s);
        ev->push_back({t, "interrupt", labels.empty() ? std::to_string(s) : labels[0]});
      });
    }
    if (hsc::HscUnit* h = hsc::HscUnit::of(&e)) {
      h->on_match([ev](uint64_t t, int n, bool timer) {
        ev->push_back({t, "cv=pv", (timer ? "HST" : "HSC") + std::to_string(n)});
      });
    }
    if (motion::MotionUnit* m = motion::MotionUnit::of(&e)) {
      m->on_step_done([ev](int ps, int step, uint64_t t) {
        ev->push_back({t, "step_end", "PSO" + std::to_string(ps) + " step " + std::to_string(step)});
      });
      m->on_home_phase([ev](int ps, const char* phase, uint64_t t) {
        ev->push_back({t, "homing", "PSO" + std::to_string(ps) + " " + phase});
      });
    }
    return 0;
  });
}

void VirtualRun::run_for(uint64_t duration_us, const std::function<void(const WatchChange&)>& on_change,
                         const std::function<void(const SimEvent&)>& on_event) {
  const uint64_t end = now_us_ + duration_us;
  if (now_us_ >= end) return;
  // Scan after scan under one hold of the lock; a client waiting for it comes in between
  // two scans (Plc::locked_steps).
  plc_.locked_steps([&](ScanEngine& e, Memory& m) {
    e.scan(now_us_);
    if (!events_->empty()) report_events(on_event);
    for (size_t i = 0; i < watches_.size(); ++i) {
      const uint32_t v = m.read(watches_[i]);
      if (!seen_[i] || v != last_[i]) {
        seen_[i] = true;
        last_[i] = v;
        if (on_change) on_change({now_us_, i, v});
      }
    }
    ++scans_;
    now_us_ += period_us_;
    return now_us_ < end;
  });
}

void VirtualRun::report_events(const std::function<void(const SimEvent&)>& on_event) {
  // Observers report in the order things happen; a unit catching up late may report an
  // earlier instant after a later one, so order by time (stable).
  std::stable_sort(events_->begin(), events_->end(),
                   [](const SimEvent& x, const SimEvent& y) { return x.t_ns < y.t_ns; });
  if (on_event)
    for (const auto& ev : *events_) on_event(ev);
  events_->clear();
}

std::vector<uint32_t> VirtualRun::values() const {
  return plc_.locked([&](const ScanEngine&, const Memory& m) {
    std::vector<uint32_t> v;
    for (const auto& a : watches_) v.push_back(m.read(a));
    return v;
  });
}

}  // namespace plc_cell
