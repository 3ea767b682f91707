#include "plc_cell/core/native/lockstep.h"

#include <cstdio>
#include <cstring>

#include "plc_cell/core/plc.h"

namespace plc_cell {

namespace {

// Whether operand o (or an instruction's own address) covers element i of area a.
bool covers(const Address& at, Operand::Kind kind, Area a, uint32_t i) {
  if (at.area != a) return false;
  uint32_t n = 1;
  if (kind == Operand::Kind::Reg32) n = 2;
  if (kind == Operand::Kind::Bits16) n = 16;
  if (kind == Operand::Kind::Bits32) n = 32;
  return i >= at.index && i < at.index + n;
}

std::string writer_of(const Program& p, Area a, uint32_t i) {
  for (const Instruction& in : p.code) {
    bool hit = false;
    if (in.op >= Op::Out && in.op <= Op::Ctr) {
      hit = covers(in.addr, Operand::Kind::Bit, a, i);
      if ((in.op == Op::Tmr && a == Area::RT) || (in.op == Op::Ctr && a == Area::RC))
        hit = hit || in.addr.index == i;
    }
    for (const Operand& o : in.operands)
      hit = hit || (o.present && o.kind != Operand::Kind::Const && covers(o.addr, o.kind, a, i));
    if (hit) return p.file + ":" + std::to_string(in.line);
  }
  return "no instruction names it";
}

std::string seconds(uint64_t us) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%llu.%06llu s", static_cast<unsigned long long>(us / 1000000),
                static_cast<unsigned long long>(us % 1000000));
  return buf;
}

std::string outcome(bool ok, const std::string& fault) { return ok ? std::string("ran") : "faulted (" + fault + ")"; }

}  // namespace

std::string first_difference(const Memory& native, const Memory& interpreter, const Program& program,
                             const std::string& what) {
  for (int k = 0; k < kAreaCount; ++k) {
    const Area a = static_cast<Area>(k);
    const bool bits = is_discrete(a);
    const uint32_t n = bits ? area_size(a) : Memory::word_count(a);
    const void* p = bits ? static_cast<const void*>(native.bits(a)) : native.words(a);
    const void* q = bits ? static_cast<const void*>(interpreter.bits(a)) : interpreter.words(a);
    if (std::memcmp(p, q, bits ? n : n * sizeof(uint16_t)) == 0) continue;  // the usual case, fast
    for (uint32_t j = 0; j < n; ++j) {
      const uint32_t x = bits ? native.bits(a)[j] : native.words(a)[j];
      const uint32_t y = bits ? interpreter.bits(a)[j] : interpreter.words(a)[j];
      if (x == y) continue;
      // RC keeps its 32-bit counters as word pairs; name the element, not the word.
      const uint32_t element =
          a == Area::RC && j >= kFirst32BitCounter ? kFirst32BitCounter + (j - kFirst32BitCounter) / 2 : j;
      const Address at{a, bits ? Width::Bit : Width::Word, element};
      return "lockstep: " + format_address(at) + " is " + std::to_string(x) + " on the native engine and " +
             std::to_string(y) + " on the interpreter after " + what + " (written by " +
             writer_of(program, a, element) + ")";
    }
  }
  return {};
}

// On the twin's engine: its memory after each run, for the primary to compare with.
class Lockstep::Recorder final : public RunObserver {
 public:
  Recorder(Lockstep& owner, const Memory& memory) : owner_(owner), memory_(memory) {}
  std::string after_run(const std::string& routine, uint64_t, bool ok, const std::string& fault) override {
    if (owner_.recorded_ == owner_.images_.size()) owner_.images_.emplace_back();
    Image& im = owner_.images_[owner_.recorded_++];
    im.routine = routine;
    im.ok = ok;
    im.fault = fault;
    im.memory = memory_;  // same sizes: the storage is reused
    return {};
  }

 private:
  Lockstep& owner_;
  const Memory& memory_;
};

Lockstep::Lockstep(const FunctionTable& functions)
    : own_twin_(std::make_unique<Plc>(functions)), twin_(*own_twin_) {
  twin_.locked([&](ScanEngine& t, Memory& m) {
    t.set_engine(EngineChoice::Interpreter);
    recorder_ = std::make_unique<Recorder>(*this, m);
    t.observe_runs(recorder_.get());
    return 0;
  });
}

Lockstep::Lockstep(Plc& twin, std::function<void()> mirror) : twin_(twin), mirror_(std::move(mirror)) {
  twin_.locked([&](ScanEngine& t, Memory& m) {
    t.set_engine(EngineChoice::Interpreter);
    recorder_ = std::make_unique<Recorder>(*this, m);
    t.observe_runs(recorder_.get());
    return 0;
  });
}

Lockstep::~Lockstep() {
  twin_.locked([](ScanEngine& t, Memory&) {
    t.observe_runs(nullptr);
    return 0;
  });
}

void Lockstep::bind(ScanEngine& primary, Memory& memory) {
  primary_ = &primary;
  memory_ = &memory;
  // A cell's twin loaded the cell's program itself; a bare twin takes the primary's.
  loads_seen_ = own_twin_ ? 0 : primary.program_loads();
  starts_seen_ = 0;
}

void Lockstep::before_scan(uint64_t now_us) {
  recorded_ = compared_ = 0;
  reported_ = false;
  const ScanEngine& p = *primary_;
  twin_.locked([&](ScanEngine& t, Memory& m) {
    if (p.program_loads() != loads_seen_) {
      // An online change, at the same scan boundary and of the same kind.
      if (p.last_load_online()) t.load_online(p.program());
      else t.load(p.program());
      loads_seen_ = p.program_loads();
    }
    if (p.run_starts() != starts_seen_) {  // a STOP -> RUN since, even if both are back in RUN
      t.set_mode(RunMode::Stop);
      t.set_mode(RunMode::Run);
      starts_seen_ = p.run_starts();
    }
    if (t.mode() != p.mode()) t.set_mode(p.mode());
    for (uint32_t x = 0; x < 256; ++x) t.set_input(x, p.input(x));
    for (uint32_t k = 0; k < 256; ++k) t.interpreter().set_timer_base(k, p.interpreter().timer_base(k));
    // Equal after the last scan (after_scan compared them): what differs now is what
    // clients, forcing and the cell's front end wrote into the primary since.
    m = *memory_;
    if (mirror_) mirror_();
    t.scan(now_us);
    return 0;
  });
}

std::string Lockstep::what(const std::string& routine, uint64_t now_us) const {
  if (routine.empty()) return "scan " + std::to_string(primary_->stats().scans) + " at " + seconds(now_us);
  return "routine " + routine + " at " + seconds(now_us);
}

std::string Lockstep::after_run(const std::string& routine, uint64_t now_us, bool ok, const std::string& fault) {
  if (reported_) return {};
  std::string why;
  if (compared_ == recorded_) {
    why = "lockstep: the native engine ran " + what(routine, now_us) + ", the interpreter did not";
  } else {
    const Image& im = images_[compared_++];
    if (im.routine != routine)
      why = "lockstep: the native engine ran " + what(routine, now_us) + ", the interpreter " +
            (im.routine.empty() ? std::string("its main program") : "routine " + im.routine) + " there";
    else if (im.ok != ok || im.fault != fault)
      why = "lockstep: the native engine " + outcome(ok, fault) + ", the interpreter " + outcome(im.ok, im.fault) +
            " in " + what(routine, now_us);
    else
      why = first_difference(*memory_, im.memory, primary_->program(), what(routine, now_us));
  }
  reported_ = !why.empty();
  return why;
}

std::string Lockstep::after_scan() {
  if (reported_) return {};
  const ScanEngine& p = *primary_;
  const std::string at = what("", p.now_us());
  if (compared_ < recorded_) {
    const Image& im = images_[compared_];
    return "lockstep: the interpreter ran " +
           (im.routine.empty() ? std::string("its main program") : "routine " + im.routine) + " in " + at +
           ", the native engine did not";
  }
  return twin_.locked([&](const ScanEngine& t, const Memory& m) -> std::string {
    if (t.mode() != p.mode()) {
      const auto state = [](const ScanEngine& e) {
        return e.mode() == RunMode::Run ? std::string("in RUN") : "stopped (" + e.fault() + ")";
      };
      return "lockstep: after " + at + " the native engine's PLC is " + state(p) + ", the interpreter's " + state(t);
    }
    if (p.mode() != RunMode::Run) return {};
    return first_difference(*memory_, m, p.program(), at);
  });
}

}  // namespace plc_cell
