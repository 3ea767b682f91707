#include "plc_cell/line/wire_sink.h"

#include <deque>

#include "plc_cell/sim/input_signal.h"

namespace plc_cell {
namespace line {

namespace {

// The edges still to come, in time order: what holds at an instant is the last one at or
// before it.
class EdgeQueue {
 public:
  explicit EdgeQueue(uint32_t initial) : value_(initial) {}
  void push(const WireEdge& e) { q_.push_back(e); }
  // The value at now_ns; *was_on: it was not 0 at some instant since the previous call.
  uint32_t at(uint64_t now_ns, bool* was_on = nullptr) {
    bool on = value_ != 0;
    while (!q_.empty() && q_.front().t_ns <= now_ns) {
      value_ = q_.front().value;
      on = on || value_ != 0;
      q_.pop_front();
    }
    if (was_on) *was_on = on;
    return value_;
  }

 private:
  uint32_t value_;
  std::deque<WireEdge> q_;
};

// X0-X15: exact edges through the counter unit, at their instants.
class ExactInput final : public WireSink {
 public:
  ExactInput(SoftCell& soft, uint32_t x, const WireModel& m, uint32_t initial)
      : WireSink(m, initial), sim_(soft.simulation()), x_(x) {
    sim_.schedule_edge(x_, 0, delay().initial() != 0);
  }

 private:
  void put(const WireEdge& e) override { sim_.schedule_edge(x_, e.t_ns, e.value != 0); }
  SimulatedCell& sim_;
  uint32_t x_;
};

// Another input: one of the simulation's signals, which the simulation owns.
class WireSignal final : public InputSignal {
 public:
  explicit WireSignal(uint32_t initial) : q_(initial) {}
  bool level(uint64_t t_us, const Memory&) override { return q_.at(t_us * 1000, &was_on_) != 0; }
  bool on_between(uint64_t, uint64_t) const override { return was_on_; }
  EdgeQueue& queue() { return q_; }

 private:
  EdgeQueue q_;
  bool was_on_ = false;  // ON at some instant since the scan before (what a capture input keeps)
};

class SampledInput final : public WireSink {
 public:
  SampledInput(SoftCell& soft, uint32_t x, const WireModel& m, uint32_t initial) : WireSink(m, initial) {
    auto s = std::make_unique<WireSignal>(delay().initial());
    signal_ = s.get();
    soft.simulation().drive(x, std::move(s));
  }

 private:
  void put(const WireEdge& e) override { signal_->queue().push(e); }
  WireSignal* signal_;  // owned by the cell's simulation, which outlives the line's sinks
};

// A relay or a register: written before the scan when its value changed.
class MemoryInput final : public WireSink, public ScanHook {
 public:
  MemoryInput(SoftCell& soft, ScanEngine& e, Memory& mem, const Address& to, const WireModel& m, uint32_t initial)
      : WireSink(m, initial), plc_(soft.plc()), mem_(mem), to_(to), q_(delay().initial()), written_(delay().initial()) {
    e.add_hook(this);
  }
  ~MemoryInput() override {
    plc_.locked([&](ScanEngine& e, Memory&) {
      e.remove_hook(this);
      return 0;
    });
  }
  void before_inputs(uint64_t now_us) override {
    const uint32_t v = q_.at(now_us * 1000);
    if (v == written_ && wrote_) return;  // the first scan writes: RUN cleared what was there
    written_ = v;
    wrote_ = true;
    mem_.write(to_, v);
  }

 private:
  void put(const WireEdge& e) override { q_.push(e); }
  Plc& plc_;
  Memory& mem_;
  Address to_;
  EdgeQueue q_;
  uint32_t written_;
  bool wrote_ = false;
};

}  // namespace

std::unique_ptr<WireSink> WireSink::make(SoftCell& soft, ScanEngine& e, Memory& mem, const Address& to,
                                         const WireModel& m, uint32_t initial) {
  if (to.area == Area::X && soft.simulation().exact(to.index))
    return std::make_unique<ExactInput>(soft, to.index, m, initial);
  if (to.area == Area::X) return std::make_unique<SampledInput>(soft, to.index, m, initial);
  return std::make_unique<MemoryInput>(soft, e, mem, to, m, initial);
}

}  // namespace line
}  // namespace plc_cell
