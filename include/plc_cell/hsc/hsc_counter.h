#pragma once
// One high-speed counter, HSC0-HSC3 (hardware: CV and PV in the chip) or HSC4-HSC7
// (software: CV and PV in DR4112...): counts the changes of its counting inputs by its
// decoding, from explicit edges or exactly from an analytic source, and requests its
// interrupt at CV=PV (docs/counters-and-interrupts.md "Event model").
#include <array>
#include <cstdint>
#include <deque>
#include <utility>

#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/count_decoder.h"
#include "plc_cell/hsc/hsc_config.h"
#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/unit_context.h"

namespace plc_cell {
namespace hsc {

int counter_source(int n);  // HSC0I ... HSC7I

class HscCounter final : public Component {
 public:
  HscCounter(UnitContext& ctx, const InputPins& pins, int n, const CounterDef& def, uint64_t window_us);

  const CounterDef& def() const { return def_; }
  EdgeSource* source() const { return src_; }
  // Which source drives the counting inputs now (again after a source is attached or
  // detached). Throws Error if two do, or one drives MASK or CLEAR.
  void bind();
  void take_quarter();              // q_, last_, epoch_ from the source at now

  void start(uint64_t t_ns) override;
  void settle() override;
  uint64_t next_event_ns() override;
  void advance_to(uint64_t t_ns) override;
  void at(uint64_t t_ns) override;
  void input_edges(uint64_t t_ns, const InputLevels& before, const InputLevels& after) override;
  void before_inputs() override;
  void after_program() override;

  uint32_t cv() const;
  void set_cv(uint32_t v);
  uint32_t pv() const;
  void read_chip();                 // FUN92: the chip's CV to DR4096...
  void write_chip(bool pv);         // FUN93
  double frequency() const;         // counts/s over the window

 private:
  bool cleared(const InputLevels& term) const;
  bool counting(const InputLevels& term) const;  // not masked, not cleared, enabled
  bool blocked() const;             // a counting input's source is too fast for its filter
  Pins pins_at(int64_t q, const InputLevels& term) const;
  void window(int dir, CountDecoder::Window* w) const;  // pins at q_ + i * dir
  uint64_t first_match(const std::array<int, 4>& first, const std::array<int, 4>& seq, int64_t to_pv) const;
  void add_count(int64_t d, bool check);
  void resync();                    // the source changed: count the jump as one transition

  UnitContext& ctx_;
  const InputPins& pins_;
  int n_;
  CounterDef def_;
  uint64_t window_ns_;
  uint32_t cv_ = 0, pv_ = 0;        // chip registers (HHSC); SHSC keeps them in R memory
  bool sw_mask_ = false, sw_clear_ = false, sw_dir_ = false;
  EdgeSource* src_ = nullptr;       // drives one or both counting inputs
  int phase_[2] = {-1, -1};         // which phase of src_ drives a, b (0 = A, 1 = B)
  int64_t q_ = 0;                   // src_ quarter at the last instant
  Pins last_;                       // counting-input levels at q_ (a source change is one transition)
  CountDecoder dec_;                // at q_
  uint64_t epoch_ = 0;              // src_->epoch() when q_ was taken
  int64_t total_ = 0;               // net counts, for the frequency
  std::deque<std::pair<uint64_t, int64_t>> hist_;
  uint64_t match_ = kNever;         // what next_event_ns() found
};

}  // namespace hsc
}  // namespace plc_cell
