#include "plc_cell/coverage/mcdc.h"

#include "plc_cell/core/interpreter.h"

namespace plc_cell {
namespace coverage {

void McdcVectors::add(size_t network, uint64_t contacts, uint64_t outcome) {
  auto& s = v_[network];
  if (s.size() < kMaxVectors) s.insert({contacts, outcome});
}

void McdcVectors::merge(const McdcVectors& o) {
  if (v_.size() < o.v_.size()) v_.resize(o.v_.size());
  for (size_t n = 0; n < o.v_.size(); ++n)
    for (const auto& x : o.v_[n]) add(n, x.first, x.second);
}

bool McdcVectors::independent(size_t n, size_t k) const {
  if (n >= v_.size() || k >= 64) return false;
  const auto& s = v_[n];
  const uint64_t bit = uint64_t(1) << k;
  for (const auto& x : s) {
    if (x.first & bit) continue;  // each pair once: from the vector where contact k is OFF
    for (auto it = s.lower_bound({x.first | bit, 0}); it != s.end() && it->first == (x.first | bit); ++it)
      if (it->second != x.second) return true;
  }
  return false;
}

McdcSampler::McdcSampler(std::vector<NetworkShape> shapes, uint8_t* seen, size_t n)
    : shapes_(std::move(shapes)), seen_(seen), acc_(n, 0) {
  vectors_.resize(shapes_.size());
}

void McdcSampler::after_program(uint64_t) {
  // A bit read once this scan: its value; not read, or read both ways (a loop, a
  // routine called twice): the network's vector of this scan is not kept.
  auto bit = [&](uint32_t i, uint64_t* v, size_t k) {
    const uint8_t s = seen_[i];
    if (s != Interpreter::kSeenOff && s != Interpreter::kSeenOn) return false;
    if (s == Interpreter::kSeenOn) *v |= uint64_t(1) << k;
    return true;
  };
  for (size_t n = 0; n < shapes_.size(); ++n) {
    const NetworkShape& sh = shapes_[n];
    if (sh.contacts.empty() || sh.contacts.size() > 64 || sh.outcomes.size() > 64) continue;
    uint64_t c = 0, o = 0;
    bool whole = true;
    for (size_t k = 0; whole && k < sh.contacts.size(); ++k) whole = bit(sh.contacts[k], &c, k);
    for (size_t k = 0; whole && k < sh.outcomes.size(); ++k) whole = bit(sh.outcomes[k], &o, k);
    if (whole) vectors_.add(n, c, o);
  }
  for (size_t i = 0; i < acc_.size(); ++i) {
    acc_[i] |= seen_[i];
    seen_[i] = 0;
  }
}

void McdcSampler::drain(std::vector<uint8_t>& into) {
  for (size_t i = 0; i < acc_.size() && i < into.size(); ++i) into[i] |= acc_[i] | seen_[i];
}

}  // namespace coverage
}  // namespace plc_cell
