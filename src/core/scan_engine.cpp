#include "plc_cell/core/scan_engine.h"

#include <algorithm>
#include <cstring>

#include "plc_cell/core/error.h"
#include "plc_cell/core/image_loop.h"

namespace plc_cell {

ScanEngine::ScanEngine(Memory& mem, const FunctionTable& functions)
    : mem_(mem), functions_(functions), interp_(mem, functions) {
  set_engine(kDefaultEngine);
}

void ScanEngine::load(const Program& program) {
  interp_.load(program);
  ++program_loads_;
  last_load_online_ = false;
  first_scan_ = true;  // a new program sees the first-scan pulse, as after a download
}

void ScanEngine::load_online(const Program& program) {
  if (mode_ != RunMode::Run) return load(program);
  interp_.load_keeping_state(program);
  ++program_loads_;
  last_load_online_ = true;
}

bool ScanEngine::set_mode(RunMode m) {
  if (m == mode_) return true;
  if (m == RunMode::Run) {
    if (!interp_.loaded()) return false;
    mem_.clear_non_retentive(retentive_);
    interp_.reset_state();
    ++run_starts_;
    fault_.clear();
    watchdog_tripped_ = false;
    first_scan_ = true;
    mode_ = RunMode::Run;
    for (auto* h : hooks_) h->on_run();
    return true;
  }
  mode_ = RunMode::Stop;
  for (uint32_t y = 0; y < area_size(Area::Y); ++y) mem_.set_bit(Area::Y, y, false);
  for (auto* h : hooks_) h->on_stop();
  return true;
}

void ScanEngine::set_engine(EngineChoice e) {
  if (e == EngineChoice::Lockstep) {
    if (lockstep_) return;
    // A twin without the subsystems would differ wherever they write: refused, not compared.
    if (!hooks_.empty())
      throw Error("lockstep: this PLC has " + std::to_string(hooks_.size()) +
                  " subsystem hook(s), so its twin must be the whole cell: build the cell with plc.engine: "
                  "lockstep or --engine lockstep");
    set_lockstep(std::make_unique<Lockstep>(functions_));
    return;
  }
  if (lockstep_) {
    runs_ = nullptr;
    lockstep_.reset();
  } else if (e == engine_) {
    return;
  }
  engine_ = e;
  interp_.use_native(e != EngineChoice::Interpreter);
}

void ScanEngine::set_lockstep(std::unique_ptr<Lockstep> twin) {
  const bool native = engine_ != EngineChoice::Interpreter;
  lockstep_ = std::move(twin);
  lockstep_->bind(*this, mem_);
  runs_ = lockstep_.get();
  engine_ = EngineChoice::Lockstep;
  if (!native) interp_.use_native(true);
}

std::string ScanEngine::engine_status() const {
  std::string s = interp_.engine_status();
  if (lockstep_)
    s = "lockstep: " + s + ", compared with the interpreter on " + lockstep_->twin_kind() +
        " after every scan and routine";
  return s;
}

bool ScanEngine::run_engine(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why) {
  const bool ok = routine.empty() ? interp_.run_main(now_us, dt_us, this) : interp_.run_routine(routine, now_us, this);
  if (!ok) *why = interp_.fault();
  return ok;
}

bool ScanEngine::run_program(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why) {
  if (runs_) return run_observed(routine, now_us, dt_us, why);
  return run_engine(routine, now_us, dt_us, why);
}

bool ScanEngine::run_observed(const std::string& routine, uint64_t now_us, uint32_t dt_us, std::string* why) {
  const bool ok = run_engine(routine, now_us, dt_us, why);
  std::string stop = runs_->after_run(routine, now_us, ok, ok ? std::string() : *why);
  if (stop.empty()) return ok;
  *why = std::move(stop);
  return false;
}

void ScanEngine::scan_observed(uint64_t now_us) {
  runs_->before_scan(now_us);
  cycle(now_us);
  const std::string why = runs_->after_scan();
  if (!why.empty()) fault_stop(why);
}

bool ScanEngine::run_routine(const std::string& label, uint64_t now_us, std::string* why) {
  return run_program(label, now_us, 0, why);
}

void ScanEngine::add_hook(ScanHook* h, unsigned phases) {
  hooks_.push_back(h);
  if (phases & ScanHook::kBeforeInputs) before_inputs_.push_back(h);
  if (phases & ScanHook::kBeforeProgram) before_program_.push_back(h);
  if (phases & ScanHook::kAfterProgram) after_program_.push_back(h);
  h->attached(*this);
}

void ScanEngine::remove_hook(ScanHook* h) {
  const auto it = std::remove(hooks_.begin(), hooks_.end(), h);
  if (it == hooks_.end()) return;
  hooks_.erase(it, hooks_.end());
  for (auto* phase : {&before_inputs_, &before_program_, &after_program_})
    phase->erase(std::remove(phase->begin(), phase->end(), h), phase->end());
  h->detached(*this);
}

void ScanEngine::update_special_relays() {
  static_assert(special::kClock100ms == special::kClock10ms + 1 && special::kClock1s == special::kClock10ms + 2 &&
                    special::kClock1min == special::kClock10ms + 3 && special::kFirstScan == special::kClock10ms + 4 &&
                    special::kAlwaysOn == special::kClock10ms + 5,
                "M1920-M1925 are one block of six bytes");
  // Clock pulses with 50 % duty: on for the second half of each period, that is in the
  // odd half periods. Every half period (5 ms, 50 ms, 0.5 s, 30 s) is a whole number of
  // the fastest one's, so the four bytes change only when the 5 ms count does.
  const uint64_t half = now_us_ / 5000;
  if (half != clock_half_) {
    clock_half_ = half;
    clock_bytes_ = (half & 1) | ((half / 10) & 1) << 8 | ((half / 100) & 1) << 16 | ((half / 6000) & 1) << 24;
  }
  const uint64_t want = clock_bytes_ | uint64_t(first_scan_) << 32 | uint64_t(1) << 40;
  // Memory::set_bit for the six bytes at once: a disabled (forced) point keeps its byte,
  // and M1926-M1927 (the two bytes after them) are kept whole.
  uint8_t* const m = mem_.bits(Area::M) + special::kClock10ms;
  static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "M1920 is the first byte of the word");
  uint64_t bytes;
  std::memcpy(&bytes, m, sizeof bytes);
  const uint64_t keep = ((bytes >> 1) & 0x0101010101010101ull) * 0xFF | 0xFFFF000000000000ull;
  bytes = (bytes & keep) | (want & ~keep);
  std::memcpy(m, &bytes, sizeof bytes);
}

void ScanEngine::fault_stop(const std::string& why) {
  fault_ = why;
  set_mode(RunMode::Stop);
}

namespace {
// The routine name of the main program, made once rather than at every scan.
const std::string kMainProgram;

// Memory::set_bit for each input, as arithmetic the compiler vectorises (a fixed cost of
// every scan): a disabled (forced) point keeps its byte.
PLC_CELL_IMAGE_LOOP void take_input_image(uint8_t* __restrict x_bits, const uint8_t* __restrict inputs) {
  for (uint32_t x = 0; x < 256; ++x) {
    const uint8_t keep = (x_bits[x] & kBitDisabled) ? 0xFF : 0;
    x_bits[x] = static_cast<uint8_t>((x_bits[x] & keep) | (inputs[x] & ~keep));
  }
}
}  // namespace

void ScanEngine::cycle(uint64_t now_us) {
  const uint32_t dt = have_time_ && now_us > now_us_ ? static_cast<uint32_t>(std::min<uint64_t>(now_us - now_us_, UINT32_MAX)) : 0;
  have_time_ = true;
  now_us_ = now_us;
  for (auto* h : before_inputs_) h->before_inputs(now_us);
  take_input_image(mem_.bits(Area::X), inputs_.data());
  ++stats_.scans;
  if (mode_ != RunMode::Run) return;
  update_special_relays();
  for (auto* h : before_program_) h->before_program(now_us);
  std::string why;
  const bool ok = run_program(kMainProgram, now_us, dt, &why);
  first_scan_ = false;
  if (!ok) {
    fault_stop(why);
    return;
  }
  for (auto* h : after_program_) h->after_program(now_us);
}

void ScanEngine::report_cycle(uint64_t exec_ns, uint64_t wake_latency_ns, uint64_t missed_periods,
                              uint64_t missed_off_cpu) {
  stats_.cycle.add(exec_ns);
  stats_.wake_latency.add(wake_latency_ns);
  stats_.overruns += missed_periods;
  stats_.overruns_off_cpu += std::min(missed_off_cpu, missed_periods);
  stats_.recent.add(now_us_, wake_latency_ns, missed_periods);
  if (mode_ == RunMode::Run && watchdog_us_ > 0 && exec_ns > watchdog_us_ * 1000) {
    watchdog_tripped_ = true;
    fault_stop("watchdog: a scan took " + std::to_string(exec_ns / 1000) + " us, the limit is " +
               std::to_string(watchdog_us_) + " us");
  }
}

}  // namespace plc_cell
