#include "plc_cell/core/plc.h"

#include "plc_cell/core/error.h"
#include "plc_cell/core/il_parser.h"

namespace plc_cell {

Plc::Plc(FunctionTable functions) : functions_(std::move(functions)), engine_(memory_, functions_) {}

void Plc::load_program_text(const std::string& text, const std::string& file) {
  load_program(parse_program(text, file, functions_));
}

void Plc::load_program_file(const std::string& path) { load_program(plc_cell::load_program_file(path, functions_)); }

void Plc::load_program(const Program& program) {
  std::lock_guard<HandoffMutex> lk(mu_);
  engine_.load(program);
}

std::vector<uint32_t> Plc::read(const Address& start, uint32_t count) const {
  check_span(start, count);
  std::vector<uint32_t> out;
  out.reserve(count);
  Address a = start;
  const uint32_t stride = element_stride(a);
  std::lock_guard<HandoffMutex> lk(mu_);
  for (uint32_t i = 0; i < count; ++i, a.index += stride) out.push_back(memory_.read(a));
  return out;
}

void Plc::write_unlocked(const Address& a, uint32_t v) {
  memory_.write(a, v);
  if (a.area == Area::X) {
    // Writing an input plays the sensor: the terminal keeps the level for later scans.
    const int n = a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
    for (int k = 0; k < n; ++k)
      if (!memory_.disabled(Area::X, a.index + k)) engine_.set_input(a.index + k, (v >> k) & 1u);
  }
}

void Plc::write(const Address& start, const std::vector<uint32_t>& values) {
  if (values.empty()) throw Error("write to " + format_address(start) + ": no values");
  check_span(start, static_cast<uint32_t>(values.size()));
  const uint64_t limit = start.width == Width::Bit ? 1 : start.width == Width::Word ? 0xFFFF : 0xFFFFFFFF;
  for (size_t i = 0; i < values.size(); ++i)
    if (values[i] > limit)
      throw Error("write to " + format_address(start) + ": value " + std::to_string(values[i]) +
                  " at position " + std::to_string(i) + " does not fit the address width");
  std::vector<Address> targets;
  for (uint32_t i = 0; i < values.size(); ++i) targets.push_back(offset_address(start, i));
  {
    std::lock_guard<HandoffMutex> lk(mu_);
    for (size_t i = 0; i < values.size(); ++i) write_unlocked(targets[i], values[i]);
  }
  commit();
}

void Plc::commit() {
  Durability* d = durability_.load();
  if (!d) return;
  uint64_t ticket;
  {
    std::lock_guard<HandoffMutex> lk(mu_);
    ticket = d->capture(engine_, memory_);
  }
  d->wait(ticket);
}

void Plc::force(const Address& a, ForceAction action) {
  if (a.width != Width::Bit) throw Error("force " + format_address(a) + ": only a single discrete can be forced");
  force_apply(a, action);
  commit();
}

void Plc::force_apply(const Address& a, ForceAction action) {
  std::lock_guard<HandoffMutex> lk(mu_);
  switch (action) {
    case ForceAction::Disable: memory_.set_disabled(a.area, a.index, true); break;
    case ForceAction::Enable: memory_.set_disabled(a.area, a.index, false); break;
    case ForceAction::Set:
    case ForceAction::Reset: {
      const bool v = action == ForceAction::Set;
      memory_.force_bit(a.area, a.index, v);
      if (a.area == Area::X) engine_.set_input(a.index, v);
      break;
    }
  }
}

bool Plc::set_mode(RunMode m) {
  std::lock_guard<HandoffMutex> lk(mu_);
  return engine_.set_mode(m);
}

RunMode Plc::mode() const {
  std::lock_guard<HandoffMutex> lk(mu_);
  return engine_.mode();
}

void Plc::set_input(uint32_t x, bool v) {
  if (x >= area_size(Area::X)) throw Error("input X" + std::to_string(x) + " out of range (X0..X255)");
  std::lock_guard<HandoffMutex> lk(mu_);
  engine_.set_input(x, v);
}

void Plc::scan(uint64_t now_us) {
  std::lock_guard<HandoffMutex> lk(mu_);
  engine_.scan(now_us);
}

}  // namespace plc_cell
