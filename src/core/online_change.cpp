#include "plc_cell/core/online_change.h"

#include <map>
#include <tuple>

#include "plc_cell/core/scan_engine.h"

namespace plc_cell {

namespace {

using EdgeKey = std::tuple<int, uint16_t, int, uint32_t, int, bool>;

EdgeKey edge_key(const Instruction& in) {
  return EdgeKey{static_cast<int>(in.op), in.fun, static_cast<int>(in.addr.area), in.addr.index,
                 static_cast<int>(in.addr.width), in.pulse};
}

// Each edge instruction's key and its occurrence among those of the same key, with its slot.
std::map<std::pair<EdgeKey, int>, uint32_t> edge_slots(const Program& p) {
  std::map<std::pair<EdgeKey, int>, uint32_t> out;
  std::map<EdgeKey, int> seen;
  for (size_t i = 0; i < p.code.size() && i < p.edge_slot_of.size(); ++i) {
    if (p.edge_slot_of[i] == ~0u) continue;
    const EdgeKey k = edge_key(p.code[i]);
    out[{k, seen[k]++}] = p.edge_slot_of[i];
  }
  return out;
}

}  // namespace

std::vector<uint32_t> carried_edges(const Program& running, const Program& next) {
  std::vector<uint32_t> from(next.edge_slots, ~0u);
  const auto old_slots = edge_slots(running);
  for (const auto& [key, slot] : edge_slots(next)) {
    const auto it = old_slots.find(key);
    if (it != old_slots.end() && slot < from.size()) from[slot] = it->second;
  }
  return from;
}

std::vector<std::string> online_change_refusals(const ScanEngine& engine, const Program& next) {
  std::vector<std::string> out;
  if (engine.mode() != RunMode::Run) return out;
  std::vector<bool> kept(256, false);
  for (const Instruction& in : next.code)
    if (in.op == Op::Tmr && in.addr.index < kept.size()) kept[in.addr.index] = true;
  const Program& running = engine.program();
  std::vector<bool> said(256, false);
  for (const Instruction& in : running.code) {
    if (in.op != Op::Tmr || in.addr.index >= kept.size()) continue;
    const uint32_t t = in.addr.index;
    if (kept[t] || said[t] || !engine.interpreter().timer_running(t)) continue;
    said[t] = true;
    out.push_back("T" + std::to_string(t) + " is timing (TMR at " + running.file + ":" + std::to_string(in.line) +
                  ") and the new program has no TMR T" + std::to_string(t) +
                  ": its contact would freeze mid-count; change it in STOP, or when its rung is off");
  }
  return out;
}

}  // namespace plc_cell
