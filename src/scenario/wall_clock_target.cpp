#include "plc_cell/scenario/wall_clock_target.h"

#include <algorithm>
#include <tuple>

#include "plc_cell/scenario/raw_value.h"
#include "plc_cell/scenario/resolution.h"
#include "plc_cell/scenario/runner.h"

namespace plc_cell {
namespace scenario {

namespace {

using Clock = std::chrono::steady_clock;

void add_unique(std::vector<Address>* v, const Address& a) {
  if (std::find(v->begin(), v->end(), a) == v->end()) v->push_back(a);
}

}  // namespace

WallClockTarget::WallClockTarget(LinkedPlc& plc, const CellConfig& config, const Case& c, WallClockOptions opt)
    : plc_(plc), config_(config), opt_(std::move(opt)), case_name_(c.name), points_(touched_points(c, config, opt_.cell)) {
  auto read = [&](const Condition& cond) {
    for (const auto& cmp : cond.all) {
      if (cmp.probe.kind != Probe::Kind::Address || cmp.probe.cell != opt_.cell) continue;
      try {
        add_unique(&poll_, address(cmp.probe));
      } catch (const Error&) {  // check_case reports it
      }
    }
  };
  for (const auto& s : c.steps) {
    read(s.cond);
    for (const auto& e : s.sequence) read(e.cond);
  }
  for (const auto& p : c.properties) read(p.when), read(p.cond);
  for (const auto& t : points_) add_unique(&poll_, t.address);  // what the case drives, for the record
}

Address WallClockTarget::address(const Probe& p) const {
  const auto it = resolved_.find(p.name);
  if (it != resolved_.end()) return it->second;
  const Address a = config_.resolve(p.name);
  resolved_.emplace(p.name, a);
  return a;
}

uint64_t WallClockTarget::since_start_us() const {
  return uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(Clock::now() - start_).count());
}

template <class F>
auto WallClockTarget::on_link(const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const CommError& e) {
    throw Error(std::string("the link to ") + plc_.describe() + " failed " + what + " at " +
                wall_time(polls_ ? since_start_us() : 0) + ": " + e.what());
  }
}

void WallClockTarget::find() {
  if (opt_.wait && opt_.wait(std::chrono::microseconds(0))) throw Stopped(opt_.why_stopped() + " before the case started");
  found_ = read_found(plc_, points_);
  if (opt_.journal) opt_.journal->begin(opt_.target_text, case_name_, found_);
}

void WallClockTarget::start(Clock::time_point zero) {
  start_ = zero;
  poll();
}

void WallClockTarget::poll() {
  const Clock::time_point sent = Clock::now();
  std::vector<uint32_t> v = on_link("polling", [&] { return poll_.empty() ? std::vector<uint32_t>() : plc_.read(poll_); });
  const Clock::time_point back = Clock::now();
  values_ = std::move(v);
  instant_us_ = uint64_t(std::chrono::duration_cast<std::chrono::microseconds>(sent - start_).count());
  slowest_us_ = std::max<uint64_t>(slowest_us_, std::chrono::duration_cast<std::chrono::microseconds>(back - sent).count());
  ++polls_;
  if (opt_.polled) opt_.polled(instant_us_, poll_, values_);
}

void WallClockTarget::scan(uint64_t t_us) {
  const Clock::time_point due = start_ + std::chrono::microseconds(t_us);
  const Clock::time_point now = Clock::now();
  const auto left = due > now ? std::chrono::duration_cast<std::chrono::microseconds>(due - now)
                              : std::chrono::microseconds(0);
  if (opt_.wait && opt_.wait(left))
    throw Stopped(opt_.why_stopped() + " at " + wall_time(since_start_us()) + ": the case did not finish");
  poll();
  // To the millisecond (well within the resolution), and never before the instant it was due.
  instant_us_ = std::max((instant_us_ + 500) / 1000 * 1000, t_us);
}

std::string WallClockTarget::check(const Probe& p, bool writing) {
  // A stimulus driven is refused by wall_clock_preflight, with its value in the words.
  if (p.kind != Probe::Kind::Address)
    return writing ? "" : p.text + ": " + plc_.describe() + " is read by its addresses and signals only (read the "
                                   "registers behind it)";
  try {
    const Address a = address(p);
    check_format(a, p.format, p.text);
    const std::string why = plc_.cannot_reach(a);
    return why.empty() ? "" : probe_label(p, config_) + ": " + why;
  } catch (const Error& e) {
    return e.what();
  }
}

Reading WallClockTarget::read(const Probe& p) {
  if (p.kind == Probe::Kind::Address) {
    const Address a = address(p);
    const auto it = std::find(poll_.begin(), poll_.end(), a);
    if (it != poll_.end() && size_t(it - poll_.begin()) < values_.size())
      return address_reading(a, values_[size_t(it - poll_.begin())], p.format);
  }
  Reading r;
  r.valid = false;
  r.text = "not polled";
  return r;
}

void WallClockTarget::touch(const Address& a) {
  if (std::find(touched_.begin(), touched_.end(), a) != touched_.end()) return;
  if (opt_.journal) opt_.journal->touched(a);  // before the write: a kill after it still restores
  touched_.push_back(a);
}

void WallClockTarget::set(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(p.text + ": " + plc_.describe() + " cannot drive it");
  const Address a = address(p);
  const uint32_t raw = raw_value(a, p.format, v, p.text);
  touch(a);
  if (is_input(a)) {
    on_link("forcing an input", [&] { plc_.force(a, raw != 0); });
    return;
  }
  on_link("writing", [&] { plc_.write(a, raw); });
}

void WallClockTarget::write(const Probe& p, const Value& v) {
  if (p.kind != Probe::Kind::Address) throw Error(p.text + ": only an address or signal is written");
  const Address a = address(p);
  const uint32_t raw = raw_value(a, p.format, v, p.text);
  touch(a);
  on_link("writing", [&] { plc_.write(a, raw); });
}

void WallClockTarget::force(const Probe& p, bool on) {
  const Address a = address(p);
  if (a.width != Width::Bit || !is_discrete(a.area)) throw Error(p.text + ": only a single discrete is forced");
  touch(a);
  on_link("forcing", [&] { plc_.force(a, on); });
  forced_.insert({int(a.area), a.index});
}

void WallClockTarget::release(const Probe* p) {
  std::vector<Address> points;
  if (p) {
    points.push_back(address(*p));
  } else {  // every point a force step of this case locked; inputs a set holds stay held
    for (const auto& f : forced_) points.push_back(Address{Area(f.first), Width::Bit, f.second});
  }
  for (const Address& a : points) {
    touch(a);
    on_link("releasing", [&] { plc_.unforce(a); });
    forced_.erase({int(a.area), a.index});
  }
}

void WallClockTarget::simulate(const Probe*) {
  throw Error("a real cell has no simulation to hand inputs back to");
}

CaseResult begin_and_run(const Case& c, WallClockTarget& t) {
  return begin_and_run(c, t, [&t] { t.begin(); });
}

CaseResult begin_and_run(const Case& c, Target& t, const std::function<void()>& begin) {
  try {
    begin();
    return run_case(c, t);
  } catch (const Error& e) {
    CaseResult r;
    r.name = c.name;
    r.file = c.file;
    r.line = c.line;
    r.failure = c.file + ":" + std::to_string(c.line) + ": " + e.what();
    return r;
  }
}

Diagnostic at_hardware_key(const Scenario& sc, const std::string& message) {
  Diagnostic d;
  d.where.file = sc.file;
  d.where.line = sc.hardware.line ? sc.hardware.line : 1;
  d.message = "key 'hardware': " + message;
  return d;
}

std::string mode_refusal(LinkedPlc& plc, const Scenario& sc) {
  if (!sc.hardware.require_run) return "";
  const std::optional<RunMode> mode = plc.mode();
  if (mode == RunMode::Run) return "";
  if (mode) return "the PLC is in STOP; this file requires RUN (or says hardware: {require_run: false})";
  return plc.cannot_read_mode() + ", so this file's requirement of RUN cannot be checked (say hardware: "
                                  "{require_run: false} once you have made sure)";
}

void said_once(std::vector<Diagnostic>* errors, std::vector<StepNote>* widened) {
  // A property is every case's: said once.
  auto key = [](const Diagnostic& d) { return std::make_tuple(d.where.file, d.where.line, d.message); };
  std::stable_sort(errors->begin(), errors->end(), [&](const Diagnostic& a, const Diagnostic& b) { return key(a) < key(b); });
  errors->erase(std::unique(errors->begin(), errors->end(), [&](const auto& a, const auto& b) { return key(a) == key(b); }),
                errors->end());
  if (!widened) return;
  auto text = [](const StepNote& n) { return std::make_tuple(n.file, n.line, n.text); };
  std::stable_sort(widened->begin(), widened->end(), [&](const auto& a, const auto& b) { return text(a) < text(b); });
  widened->erase(std::unique(widened->begin(), widened->end(), [&](const auto& a, const auto& b) { return text(a) == text(b); }),
                 widened->end());
}

std::vector<Diagnostic> refusals_on(LinkedPlc& plc, const std::string& target, const Scenario& sc,
                                    const CellConfig& config, const WallClockRules& rules, std::vector<Case>* cases,
                                    std::vector<StepNote>* widened, bool connected) {
  std::vector<Diagnostic> errors;
  const std::string why = sc.hardware.refuses(target);
  if (!why.empty()) errors.push_back(at_hardware_key(sc, why));
  if (connected) {
    const std::string mode = mode_refusal(plc, sc);
    if (!mode.empty()) errors.push_back(at_hardware_key(sc, mode));
  }
  for (Case& c : *cases) {
    WallClockTarget t(plc, config, c, {});
    for (auto& e : check_case(c, t)) errors.push_back(e);
    Preflight p = wall_clock_preflight(c, rules, config);
    errors.insert(errors.end(), p.errors.begin(), p.errors.end());
    if (widened) widened->insert(widened->end(), p.widened.begin(), p.widened.end());
    c = std::move(p.adjusted);
  }
  said_once(&errors, widened);
  return errors;
}

std::string forces_and_writes(const std::vector<Case>& cases, const CellConfig& config) {
  std::vector<TouchedPoint> points;
  for (const auto& c : cases)
    for (const auto& p : touched_points(c, config)) points.push_back(p);
  return forces_and_writes(points);
}

std::string forces_and_writes(const std::vector<TouchedPoint>& points) {
  std::vector<std::string> forced, written;
  for (const auto& p : points) {
    auto& list = p.held ? forced : written;
    if (std::find(list.begin(), list.end(), p.label) == list.end()) list.push_back(p.label);
  }
  for (const auto& f : forced) written.erase(std::remove(written.begin(), written.end(), f), written.end());
  auto join = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& x : v) s += (s.empty() ? "" : ", ") + x;
    return s.empty() ? std::string("nothing") : s;
  };
  return "forces " + join(forced) + "; writes " + join(written);
}

}  // namespace scenario
}  // namespace plc_cell
