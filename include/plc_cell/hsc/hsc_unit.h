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
//
// The unit composes parts (component.h), each its own file: the inputs X0-X15
// (input_pins.h) and their explicit edges (terminal_edges.h), a counter (hsc_counter.h)
// or timer (hs_timer.h) per configured number, the edge interrupts (edge_interrupts.h),
// a pulse measurement per measured input (measured_input.h) and the output image
// (output_image.h). Only configured parts are called per scan and per event.
#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/hsc/component.h"
#include "plc_cell/hsc/edge_interrupts.h"
#include "plc_cell/hsc/edge_source.h"
#include "plc_cell/hsc/hs_timer.h"
#include "plc_cell/hsc/hsc_config.h"
#include "plc_cell/hsc/hsc_counter.h"
#include "plc_cell/hsc/input_pins.h"
#include "plc_cell/hsc/measured_input.h"
#include "plc_cell/hsc/output_image.h"
#include "plc_cell/hsc/pulse_meter.h"
#include "plc_cell/hsc/pulse_source.h"
#include "plc_cell/hsc/scan_debounce.h"
#include "plc_cell/hsc/terminal_edges.h"
#include "plc_cell/hsc/unit_context.h"
#include "plc_cell/timeline/event_source.h"
#include "plc_cell/timeline/scheduler.h"

namespace plc_cell {

class Plc;

namespace hsc {

// The interrupt source ids and labels (core/interrupt_sources.h), as the counters name them.
using namespace irq;

class HscUnit final : public ScanHook, public timeline::EventSource {
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
  bool simulates(int x) const { return terminal_.simulates(x); }
  PulseSource* source(const std::string& name);
  // Another analytic source (owned by the caller, e.g. a pulse-output axis wired to
  // inputs) on X pin_a (phase 0) and pin_b (phase 1, -1: none). Throws Error if a pin
  // is outside X0-X15 or already driven.
  void attach_source(EdgeSource* s, int pin_a, int pin_b);
  void detach_source(EdgeSource* s);
  // Output y belongs to a pulse generator: the Y relay does not reach the terminal
  // (the I/O refresh and its observers skip it).
  void own_output(uint32_t y, bool owned = true) { outputs_.own(y, owned); }
  bool source_on(int x) const { return x >= 0 && x < 16 && pins_.driven(x); }
  void set_source_rate(const std::string& name, double hz);  // from the last processed instant
  void preset(int n, int64_t value);  // sets the CV now (chip, register or timer); 0 clears
  int64_t count(int n) const;       // CV now: chip (HHSC), register (SHSC), timer value (HST)
  double frequency(int n) const;    // counts/s over the configured window
  // Pulse measurement of input x now (counters.pulse_measurement; all 0 if x is not
  // measured): width and period of the last full cycle, exact to the ns.
  PulseReading pulse(int x) const;
  const HscConfig& config() const { return cfg_; }

  using OutputObserver = OutputImage::Observer;
  void on_output(OutputObserver f) { outputs_.observe(std::move(f)); }
  // Every CV=PV match of counter n (HSC0-7; timer: HST0-3) at its instant, whether
  // or not an interrupt routine runs (`plc_cell sim --trace`).
  using MatchObserver = hsc::MatchObserver;
  void on_match(MatchObserver f) { ctx_.match_obs.push_back(std::move(f)); }

  // ---- in the scheduler's loop ----
  void start(uint64_t t_ns) override;
  void stop() override;
  void settle() override;
  uint64_t next_event_ns() override;
  void advance_to(uint64_t t_ns) override;
  void at(uint64_t t_ns) override;

 private:
  uint64_t now() const { return ctx_.now(); }
  bool running() const { return ctx_.running(); }
  void bind_counters();
  void compose();
  // routines: the interrupt sources (bits) without whose routines the part never has an
  // event; while the bound program has none of them, the scheduler's loop does not ask
  // it (0: always asked).
  template <class T>
  void add_part(T* p, uint64_t routines = 0) {
    parts_.push_back(p);
    routines_of_.push_back(routines);
    if (Component::steps_of<T>() & timeline::EventSource::kSettles) settling_.push_back(p);
    if (Component::steps_of<T>() & timeline::EventSource::kAdvances) advancing_.push_back(p);
  }
  void act(uint64_t t, const std::vector<std::pair<int, bool>>& group);  // explicit edges at t

  Plc& plc_;
  UnitContext ctx_;
  HscConfig cfg_;
  InputPins pins_;
  TerminalEdges terminal_;
  OutputImage outputs_;
  std::vector<std::unique_ptr<PulseSource>> sources_;
  std::vector<HscCounter> counters_;  // HSC0-HSC7, configured or not (FUN92/93 reach all)
  std::vector<HsTimer> timers_;       // HST0-HST3
  HstaTimer hsta_;
  TimeBaseInterrupt time_base_;
  EdgeInterrupts edge_irq_;
  std::vector<MeasuredInput> meters_;
  std::array<int, 16> meter_of_{};    // index in meters_ of input x, -1: not measured
  std::vector<std::pair<int, ScanDebounce>> scan_filters_;  // the filtered ones of X16-X35
  std::vector<Component*> parts_;     // the configured parts, in the order they act
  std::vector<uint64_t> routines_of_;  // of each part (add_part)
  // The parts that may have events under the routines of the bound program (in order),
  // made again when the program's routines change.
  std::vector<Component*> timed_;
  uint64_t timed_for_ = UINT64_MAX;  // the routines timed_ was made for
  // Those with code for settle / advance_to (Component::steps_of), in the same order.
  std::vector<Component*> settling_, advancing_;
  std::vector<Component*> scanned_;   // those with work at the scans: the counters
};

}  // namespace hsc
}  // namespace plc_cell
