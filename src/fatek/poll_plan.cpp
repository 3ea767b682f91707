#include "plc_cell/fatek/poll_plan.h"

#include <algorithm>
#include <map>
#include <tuple>

namespace plc_cell {
namespace fatek {
namespace {

using Key = std::tuple<int, int, uint32_t>;  // area, width, element index
Key key_of(const Address& a) { return Key{int(a.area), int(a.width), a.index}; }

// Index distance between consecutive elements (X0 -> X1: 1, WX0 -> WX16: 16, DR0 -> DR2: 2).
uint32_t step(const Address& a) {
  if (is_discrete(a.area)) return a.width == Width::Bit ? 1 : a.width == Width::Word ? 16 : 32;
  if (a.width == Width::DWord && !(a.area == Area::RC && a.index >= kFirst32BitCounter)) return 2;
  return 1;
}
// Elements of one run share (area, width, phase); consecutive ones differ by 1 in ordinal.
uint32_t ordinal(const Address& a) { return a.index / step(a); }
uint32_t phase(const Address& a) { return a.index % step(a); }

// Every requested element, grouped into runs of one (area, width, phase), ordered.
using ByType = std::map<std::tuple<int, int, uint32_t, bool>, std::map<uint32_t, Address>>;

// What is left of a run once its full block frames are planned, to be packed.
struct Piece {
  Address start;
  uint32_t count;
  uint32_t weight;
};

// The end of the run that starts at it: consecutive ordinals, reading through gaps of up
// to kMaxGap elements; last_ord is the run's last ordinal.
std::map<uint32_t, Address>::const_iterator run_end(const std::map<uint32_t, Address>& elems,
                                                    std::map<uint32_t, Address>::const_iterator it, uint32_t* last_ord) {
  const Address first = it->second;
  *last_ord = it->first;
  auto next = std::next(it);
  while (next != elems.end() && next->first - *last_ord <= kMaxGap + 1) {
    try {
      check_span(first, next->first - it->first + 1);
    } catch (const Error&) {
      break;  // e.g. RC199 -> RC200 crosses into the 32-bit counters
    }
    *last_ord = next->first;
    ++next;
  }
  return next;
}

// Each run: its full block frames into plan, its remainder into pieces.
void cut_runs(const ByType& by_type, PollPlan* plan, std::vector<Piece>* pieces) {
  for (const auto& t : by_type) {
    const auto& elems = t.second;
    auto it = elems.begin();
    while (it != elems.end()) {
      const Address first = it->second;
      uint32_t last_ord = 0;
      const auto next = run_end(elems, it, &last_ord);
      const uint32_t span = last_ord - it->first + 1;
      uint32_t done = 0;
      while (span - done > max_block(first)) {
        Request r;
        r.start = offset_address(first, done);
        r.cmd = first.width == Width::Bit ? Cmd::ReadDiscretes : Cmd::ReadRegisters;
        r.count = max_block(first);
        plan->requests.push_back(r);
        done += r.count;
      }
      const uint32_t n = span - done;
      pieces->push_back({offset_address(first, done), n, n * weight(first)});
      it = next;
    }
  }
}

// First-fit decreasing into frames of weight 64.
std::vector<std::vector<Piece>> pack(std::vector<Piece> pieces) {
  std::stable_sort(pieces.begin(), pieces.end(), [](const Piece& a, const Piece& b) { return a.weight > b.weight; });
  std::vector<std::vector<Piece>> bins;
  std::vector<uint32_t> load;
  for (const auto& p : pieces) {
    bool placed = false;
    if (p.weight <= kMaxMixedReadWeight) {
      for (size_t b = 0; b < bins.size() && !placed; ++b)
        if (load[b] + p.weight <= kMaxMixedReadWeight) {
          bins[b].push_back(p);
          load[b] += p.weight;
          placed = true;
        }
    }
    if (!placed) {
      bins.push_back({p});
      load.push_back(p.weight > kMaxMixedReadWeight ? kMaxMixedReadWeight + 1 : p.weight);
    }
  }
  return bins;
}

}  // namespace

PollPlan plan_poll(const std::vector<PollItem>& items) {
  ByType by_type;
  for (const auto& it : items)
    for (uint32_t i = 0; i < it.count; ++i) {
      const Address a = offset_address(it.start, i);
      const bool counter32 = a.area == Area::RC && a.index >= kFirst32BitCounter;
      by_type[{int(a.area), int(a.width), phase(a), counter32}][ordinal(a)] = a;
    }
  PollPlan plan;
  std::vector<Piece> pieces;
  cut_runs(by_type, &plan, &pieces);
  // A frame holding one piece is a block read (44/46); several pieces share one mixed
  // read (48).
  for (const auto& bin : pack(std::move(pieces))) {
    Request r;
    if (bin.size() == 1) {
      r.start = bin[0].start;
      r.count = bin[0].count;
      r.cmd = r.start.width == Width::Bit ? Cmd::ReadDiscretes : Cmd::ReadRegisters;
    } else {
      r.cmd = Cmd::MixedRead;
      for (const auto& p : bin)
        for (uint32_t i = 0; i < p.count; ++i) r.points.push_back(offset_address(p.start, i));
    }
    plan.requests.push_back(r);
  }
  return plan;
}

std::vector<std::vector<uint32_t>> run_poll(Client& c, const std::vector<PollItem>& items, const PollPlan& plan) {
  std::map<Key, uint32_t> got;
  for (const auto& r : plan.requests) {
    const Response rsp = c.transact(r);
    if (r.cmd == Cmd::MixedRead) {
      for (size_t i = 0; i < r.points.size() && i < rsp.values.size(); ++i) got[key_of(r.points[i])] = rsp.values[i];
    } else {
      for (uint32_t i = 0; i < r.count && i < rsp.values.size(); ++i)
        got[key_of(offset_address(r.start, i))] = rsp.values[i];
    }
  }
  std::vector<std::vector<uint32_t>> out;
  for (const auto& it : items) {
    std::vector<uint32_t> v;
    for (uint32_t i = 0; i < it.count; ++i) v.push_back(got.at(key_of(offset_address(it.start, i))));
    out.push_back(std::move(v));
  }
  return out;
}

}  // namespace fatek
}  // namespace plc_cell
