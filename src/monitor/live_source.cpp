#include "plc_cell/monitor/live_source.h"

#include <algorithm>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/cell_extension.h"
#include "plc_cell/config/program_changes.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"

namespace plc_cell {
namespace monitor {
namespace {

// What tells one loaded program from another without copying it under the lock: how many
// loads the engine has seen (a change of a constant alone is a new program), its file, size
// and a hash of every instruction's operation, address and line.
std::vector<uint64_t> fingerprint_of(const ScanEngine& se) {
  const Program& p = se.program();
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint64_t v) { h = (h ^ v) * 1099511628211ull; };
  for (const auto& i : p.code) {
    mix(uint64_t(i.op) | uint64_t(i.fun) << 8 | uint64_t(i.addr.area) << 24 | uint64_t(i.addr.index) << 32);
    mix(uint64_t(uint32_t(i.line)) | uint64_t(i.operands.size()) << 32);
  }
  return {h, p.code.size(), std::hash<std::string>()(p.file), se.program_loads()};
}

}  // namespace

LiveSource::LiveSource(const ServerContext& c, std::string name)
    : plc_(c.plc),
      config_(c.config),
      extensions_(c.extensions),
      servers_(c.servers),
      changes_(c.changes),
      name_(std::move(name)) {}

LiveSource::~LiveSource() {
  std::lock_guard<std::mutex> lk(mu_);
  if (!seen_) return;
  plc_.locked([&](ScanEngine& se, Memory&) {
    if (se.interpreter().recording() == seen_.get()) se.interpreter().record_into(nullptr);
    return 0;
  });
}

std::shared_ptr<const ProgramView> LiveSource::program() const {
  std::lock_guard<std::mutex> lk(mu_);
  auto fp = plc_.locked([](const ScanEngine& se, const Memory&) { return fingerprint_of(se); });
  if (view_ && fp == fingerprint_) return view_;
  // Changed (or first): copy it once. Another reload between the two locks only makes the
  // next call copy again.
  auto v = std::make_shared<ProgramView>();
  plc_.locked([&](const ScanEngine& se, const Memory&) {
    v->program = se.program();
    fingerprint_ = fingerprint_of(se);
    return 0;
  });
  v->file = v->program.file;
  v->text = changes_ ? changes_->text() : file_text(v->program.file).value_or("");
  if (config_) v->signals = config_->signals;
  v->version = view_ ? view_->version + 1 : 1;
  view_ = v;
  return view_;
}

Frame LiveSource::read(const std::vector<Address>& addrs) {
  for (const auto& a : addrs) check_span(a, 1);
  Frame f;
  f.values.reserve(addrs.size());
  f.forced.reserve(addrs.size());
  plc_.locked([&](const ScanEngine& se, const Memory& m) {
    f.scan = se.stats().scans;
    f.t_us = se.now_us();
    f.mode = se.mode();
    for (const auto& a : addrs) {
      f.values.push_back(m.read(a));
      f.forced.push_back(a.width == Width::Bit && is_discrete(a.area) && m.disabled(a.area, a.index));
    }
    return 0;
  });
  return f;
}

CellStatus LiveSource::status() {
  CellStatus s;
  plc_.locked([&](const ScanEngine& se, const Memory& m) {
    s.mode = se.mode();
    s.scan = se.stats();
    s.forced = m.disabled_points();
    s.engine = se.engine_status();
    if (!se.fault().empty()) s.note = "stopped: " + se.fault();
    return 0;
  });
  s.mode_switchable = true;
  // Each extension takes the lock for its own copy.
  if (extensions_)
    for (const auto& x : *extensions_)
      for (auto& e : x->status(plc_)) s.extensions.push_back(std::move(e));
  if (servers_)
    for (const Server* srv : servers_()) s.servers.emplace_back(srv->describe(), srv->status());
  return s;
}

void LiveSource::write(const Address& start, const std::vector<uint32_t>& values) { plc_.write(start, values); }

void LiveSource::force(const Address& bit, ForceAction action) { plc_.force(bit, action); }

void LiveSource::set_mode(RunMode mode) {
  if (!plc_.set_mode(mode)) throw Error("RUN refused: no program is loaded");
}

std::optional<std::vector<uint8_t>> LiveSource::coverage() {
  std::lock_guard<std::mutex> lk(mu_);
  bool available = true;
  std::vector<uint8_t> out;
  plc_.locked([&](ScanEngine& se, Memory&) {
    Interpreter& in = se.interpreter();
    const size_t n = se.program().code.size();
    if (!seen_ || seen_size_ != n || in.recording() != seen_.get()) {
      // Someone else records (a scenario run's coverage): theirs stays.
      if (in.recording() && in.recording() != seen_.get()) {
        available = false;
        return 0;
      }
      // First request, or the program was reloaded (which stopped the recording).
      seen_ = std::make_unique<uint8_t[]>(n ? n : 1);
      std::fill(seen_.get(), seen_.get() + (n ? n : 1), uint8_t(0));
      seen_size_ = n;
      in.record_into(seen_.get());
    }
    out.assign(seen_.get(), seen_.get() + seen_size_);
    return 0;
  });
  if (!available) return std::nullopt;
  return out;
}

}  // namespace monitor
}  // namespace plc_cell
