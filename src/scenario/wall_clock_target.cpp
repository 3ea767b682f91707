#include "plc_cell/scenario/wall_clock_target.h"

#include <algorithm>

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
    : plc_(plc), config_(config), opt_(std::move(opt)), case_name_(c.name), points_(touched_points(c, config)) {
  auto read = [&](const Condition& cond) {
    for (const auto& cmp : cond.all) {
      if (cmp.probe.kind != Probe::Kind::Address) continue;
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

void WallClockTarget::begin() {
  if (opt_.wait && opt_.wait(std::chrono::microseconds(0))) throw Stopped(opt_.why_stopped() + " before the case started");
  found_ = read_found(plc_, points_);
  if (opt_.journal) opt_.journal->begin(opt_.target_text, case_name_, found_);
  start_ = Clock::now();
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

}  // namespace scenario
}  // namespace plc_cell
