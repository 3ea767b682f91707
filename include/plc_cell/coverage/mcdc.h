#pragma once
// MC/DC of a network's contacts, in the unique-cause form (docs/coverage.md): after every
// scan, the values each contact of a network read and the results its coils and FUNs
// received are kept as one vector; a contact is shown to decide its network when two kept
// vectors differ in that contact alone and in the outcome.
#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "plc_cell/core/program.h"
#include "plc_cell/core/scan_engine.h"

namespace plc_cell {
namespace coverage {

// The contacts (instruction indexes) and outcomes (coils, FUNs) of each network.
struct NetworkShape {
  std::vector<uint32_t> contacts, outcomes;
};

// What the scans showed of each network: its distinct (contacts, outcome) vectors.
class McdcVectors {
 public:
  // A network keeps at most this many distinct vectors (a register-driven network can
  // make many); contacts beyond 64 in one network are not measured.
  static constexpr size_t kMaxVectors = 4096;

  void resize(size_t networks) { v_.resize(networks); }
  void add(size_t network, uint64_t contacts, uint64_t outcome);
  void merge(const McdcVectors& o);
  // Contact k of network n decided it alone in some pair of scans.
  bool independent(size_t n, size_t k) const;

 private:
  std::vector<std::set<std::pair<uint64_t, uint64_t>>> v_;
};

// Samples every network after each scan of the program (the seen bytes of that scan), then
// adds them to acc and clears them for the next scan.
class McdcSampler final : public ScanHook {
 public:
  McdcSampler(std::vector<NetworkShape> shapes, uint8_t* seen, size_t n);
  void after_program(uint64_t now_us) override;
  // The scans' seen bytes so far, ORed, the current scan's included.
  void drain(std::vector<uint8_t>& into);
  const McdcVectors& vectors() const { return vectors_; }

 private:
  std::vector<NetworkShape> shapes_;
  uint8_t* seen_;
  std::vector<uint8_t> acc_;
  McdcVectors vectors_;
};

}  // namespace coverage
}  // namespace plc_cell
