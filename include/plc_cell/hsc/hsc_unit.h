#pragma once
// High-speed counters HSC0-HSC7, high-speed timers HSTA/HST0-HST3 and the input-edge
// and time-base interrupt sources of one soft PLC: a scan hook and a source of the
// cell's scheduler (timeline/scheduler.h).
//
// Event model (docs/counters-and-interrupts.md): the unit's events are CV=PV matches,
// timer expiries, time-base ticks, scheduled input edges and edges of the analytic
// pulse sources on interrupt inputs; each is found in O(1) from the sources' exact
// positions, so the cost per scan does not depend on the input frequency. The
// scheduler runs them, with the other subsystems' events (the pulse axes' step ends),
// in time order, and the interrupt routines at their instants.
// The unit also applies the capture inputs and the digital input filter (§9.6-9.7):
// on the exact edges of X0-X15 and on the scan's samples of X16-X35.
#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <queue>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/hsc/edge_source.h"
#include "plc_cell/hsc/hsc_config.h"
#include "plc_cell/hsc/pulse_meter.h"
#include "plc_cell/hsc/pulse_source.h"
#include "plc_cell/hsc/scan_debounce.h"
#include "plc_cell/timeline/event_source.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {

class Plc;

namespace hsc {

// The interrupt source ids and labels (core/interrupt_sources.h), as the counters name them.
using namespace irq;

class HscUnit : public ScanHook, public timeline::EventSource {
 public:
  // Installs itself as a hook of plc's engine; throws Error if the config does not fit.
  HscUnit(Plc& plc, HscConfig cfg);
  ~HscUnit() override;
  HscUnit(const HscUnit&) = delete;
  HscUnit& operator=(const HscUnit&) = delete;

  // The unit installed on an engine (what the FUNs use), or null.
  static HscUnit* of(ScanEngine* engine);

  void before_inputs(uint64_t now_us) override;
  void after_program(uint64_t now_us) override;
  void before_program(uint64_t now_us) override;
  void attached(ScanEngine& e) override;  // FUN handlers find the unit through of()
  void detached(ScanEngine& e) override;

  // ---- instructions (called from the interpreter, lock held) ----
  void read_chip(int cn);               // FUN92 HSCTR
  void write_chip(int cn, bool pv);     // FUN93 HSCTW: D=0 CV, D=1 PV
  bool set_enabled(const std::string& label, bool on);  // FUN145 EN / FUN146 DIS
  void immediate_io(const Address& first, uint32_t n);   // FUN74 IMDIO

  // ---- simulation and observation (hold the Plc lock) ----
  // An exact-time switch edge of the cell's simulation at the terminal; a filtered input
  // sees it through its filter.
  void schedule_edge(int x, uint64_t t_ns, bool level);
  // A periodic switch on X0-X15 (the cell YAML's simulation pulse): on for width of
  // every period from delay, as exact edges (one event per edge: for fast signals
  // use a PulseSource, whose edges cost nothing).
  void add_pulse_train(int x, uint64_t period_ns, uint64_t width_ns, uint64_t delay_ns);
  // Something outside the simulation (a scenario's set, a ROS topic) plays X0-X15 input x
  // (muted true): the scheduled edges and the pulse train of x no longer reach the
  // terminal, so neither the image nor a counter or an edge interrupt sees them. Unmuted,
  // the simulation plays x again from the level it gives now (a level set from outside
  // and not yet scanned is dropped).
  void mute_simulation(int x, bool muted);
  // Scheduled edges or a pulse train play input x.
  bool simulates(int x) const { return x >= 0 && x < 16 && simulated_[x]; }
  PulseSource* source(const std::string& name);
  // Another analytic source (owned by the caller, e.g. a pulse-output axis wired to
  // inputs) on X pin_a (phase 0) and pin_b (phase 1, -1: none). Throws Error if a pin
  // is outside X0-X15 or already driven.
  void attach_source(EdgeSource* s, int pin_a, int pin_b);
  void detach_source(EdgeSource* s);
  // Output y belongs to a pulse generator: the Y relay does not reach the terminal
  // (the I/O refresh and its observers skip it).
  void own_output(uint32_t y, bool owned = true) { if (y < owned_y_.size()) owned_y_[y] = owned; }
  bool source_on(int x) const { return x >= 0 && x < 16 && pin_src_[x] != nullptr; }
  void set_source_rate(const std::string& name, double hz);  // from the last processed instant
  void preset(int n, int64_t value);  // sets the CV now (chip, register or timer); 0 clears
  int64_t count(int n) const;       // CV now: chip (HHSC), register (SHSC), timer value (HST)
  double frequency(int n) const;    // counts/s over the configured window
  // Pulse measurement of input x now (counters.pulse_measurement; all 0 if x is not
  // measured): width and period of the last full cycle, exact to the ns.
  PulseReading pulse(int x) const;
  const HscConfig& config() const { return cfg_; }

  using OutputObserver = std::function<void(uint64_t t_ns, uint32_t y, bool level)>;
  void on_output(OutputObserver f) { output_obs_.push_back(std::move(f)); }
  // Every CV=PV match of counter n (HSC0-7; timer: HST0-3) at its instant, whether
  // or not an interrupt routine runs (`plc_cell sim --trace`).
  using MatchObserver = std::function<void(uint64_t t_ns, int n, bool timer)>;
  void on_match(MatchObserver f) { match_obs_.push_back(std::move(f)); }

  // ---- in the scheduler's loop ----
  void start(uint64_t t_ns) override;
  void stop() override;
  void settle() override;
  uint64_t next_event_ns() override;
  void advance_to(uint64_t t_ns) override;
  void at(uint64_t t_ns) override;

 private:
  static constexpr uint64_t kTick = 100000;  // 0.1 ms in ns

  struct Counter {
    int n = 0;
    CounterDef def;
    uint32_t cv = 0, pv = 0;  // chip registers (HHSC); SHSC keeps them in R memory
    bool sw_mask = false, sw_clear = false, sw_dir = false;
    EdgeSource* src = nullptr;   // drives one or both counting inputs
    int phase[2] = {-1, -1};     // which phase of src drives a, b (0 = A, 1 = B)
    int64_t q = 0;               // src quarter at cur_ns_
    Pins last;                   // counting-input levels at q (a source change is one transition)
    DecodeState dec;             // the TRi enhanced decoder's memory, at q
    uint64_t epoch = 0;          // src->epoch() when q was taken
    int64_t total = 0;           // net counts, for the frequency
    std::deque<std::pair<uint64_t, int64_t>> hist;
    uint32_t t_cv0 = 0;          // HST: CV at t_base
    uint64_t t_base = 0;
  };
  struct Edge {
    uint64_t t;
    uint64_t seq;
    int x;
    bool level;
    bool commit = false;  // the filter's output: valid only if gen is still the pin's
    uint64_t gen = 0;
    bool simulated = false;  // from schedule_edge: muted with the pin
    bool operator>(const Edge& o) const { return t != o.t ? t > o.t : seq > o.seq; }
  };

  uint64_t now() const { return sched_.now_ns(); }
  bool running() const { return sched_.running(); }
  timeline::InterruptController& irq() const { return sched_.interrupts(); }
  void advance_counters(uint64_t t);
  void refresh_outputs(uint32_t first, uint32_t n);

  bool term(int x, uint64_t t) const;     // terminal level of X0-X15
  bool counting(const Counter& c) const;  // not masked, not cleared, enabled
  bool cleared(const Counter& c) const;
  Pins pins_at(const Counter& c, int64_t q) const;
  // CV changes at the next boundaries the source crosses: first[i] at boundary i+1,
  // seq[i] at boundaries 4k+i+1 for every k >= 1 (they repeat from the fifth on).
  void weights(const Counter& c, std::array<int, 4>* first, std::array<int, 4>* seq) const;
  DecodeState decoder_after(const Counter& c, int64_t k) const;  // after k boundaries from c.q
  int delta(Counter& c, Pins before, Pins after);  // by the counter's rule; steps c.dec
  uint64_t next_match(const Counter& c) const;
  uint32_t get_cv(const Counter& c) const;
  uint32_t get_pv(const Counter& c) const;
  void set_cv(Counter& c, uint32_t v);
  void add_count(Counter& c, int64_t d, bool check);
  uint32_t hst_cv(const Counter& c, uint64_t t) const;
  uint64_t hst_match(const Counter& c) const;
  uint64_t hsta_next() const;
  int active_time_base() const;
  uint64_t next_pin_edge(int x, bool rising) const;
  bool blocked(int x) const;                 // an analytic source too fast for x's filter
  bool blocked(const Counter& c) const;      // one of its counting inputs is
  void raw_edge(const Edge& e, std::vector<std::pair<int, bool>>* group);
  bool source_was_on(int x) const;           // capture of an analytic pin since the last image
  void bind_pins(EdgeSource* s, int pin_a, int pin_b);
  void bind_counters();
  void take_quarter(Counter& c);             // c.q, c.last, c.epoch from the source at cur_ns_
  void resync(Counter& c);                   // the source changed: count the jump as one transition
  void advance_meters(uint64_t t);           // analytic edges of measured pins up to t

  ScanEngine& engine_;
  Memory& mem_;
  Plc& plc_;
  timeline::Scheduler& sched_;
  HscConfig cfg_;
  std::vector<std::unique_ptr<PulseSource>> sources_;
  std::array<EdgeSource*, 16> pin_src_{};   // analytic driver of each X0-X15
  std::array<int, 16> pin_phase_{};
  std::array<bool, 16> term_{};              // explicit terminal levels after the filter
  std::array<bool, 16> raw_{};               // ... before the filter (what the terminal shows)
  std::array<uint64_t, 16> gen_{};           // filter: a raw change cancels the pending output
  std::array<bool, 16> latch_{};             // capture: ON at some instant since the last image
  std::array<int64_t, 16> cap_q_{};          // capture of an analytic pin: quarter at the last image
  std::array<bool, 16> simulated_{};         // scheduled edges or a pulse train play the pin
  std::array<bool, 16> muted_{};             // ... but something outside plays it now
  std::array<bool, 16> sim_raw_{};           // the raw level the scheduled edges gave, muted or not
  std::array<ScanDebounce, kFilteredInputs - 16> scan_filter_;  // X16-X35
  std::array<Counter, 8> counters_;
  // Pulse measurement of X0-X15. Explicit edges reach a meter as they act; an analytic
  // pin's edges are found from the quarters crossed (at most the last two cycles of a
  // span matter, so the cost does not depend on the frequency).
  struct Meter {
    bool on = false;
    PulseMeter m;
    EdgeSource* src = nullptr;  // the analytic driver the quarter q belongs to
    int64_t q = 0;
    bool level = false;         // at q
    uint64_t epoch = 0;
  };
  std::array<Meter, 16> meters_;
  struct Train {
    int x;
    uint64_t period, width, delay;
    uint64_t next_after(uint64_t t, bool* rising) const;
    bool level_at(uint64_t t) const { return t >= delay && (t - delay) % period < width; }
  };
  std::priority_queue<Edge, std::vector<Edge>, std::greater<Edge>> edges_;
  std::vector<Train> trains_;
  uint64_t edge_seq_ = 0;
  // What next_event_ns() found, for at() of the chosen instant.
  std::array<uint64_t, 8> match_{};
  uint64_t hsta_next_ = kNever, tb_next_ = kNever;
  int tb_ = -1;
  std::array<uint64_t, 32> pin_edge_{};
  uint64_t prev_ns_ = 0;     // the instant before the present one (pulse trains)
  uint64_t run_ns_ = 0;      // when RUN started: the time bases count from here
  uint16_t hsta_pv_ = 0;
  uint32_t hsta_cv0_ = 0;
  uint64_t hsta_t0_ = 0;
  // Plain arrays, not vector<bool>: every scan compares all 256 outputs.
  std::array<bool, 256> phys_y_{};
  std::array<bool, 256> owned_y_{};
  std::vector<OutputObserver> output_obs_;
  std::vector<MatchObserver> match_obs_;
};

}  // namespace hsc
}  // namespace plc_cell
