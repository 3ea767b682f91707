#pragma once
// The outputs Y0-Y255 at the terminals, as the I/O refresh leaves them: the changes reach
// the observers (`plc_cell sim --trace`, tests) and the pulse sources that follow an
// output. An output owned by a pulse generator does not reach the terminal.
//
// Every scan compares the whole image, so the comparison runs eight outputs at a time
// (the memory keeps one byte per point) and looks at single points only where one changed.
#include <array>
#include <cstdint>
#include <functional>
#include <vector>

#include "plc_cell/core/memory.h"
#include "plc_cell/hsc/pulse_source.h"

namespace plc_cell {
namespace hsc {

class OutputImage {
 public:
  using Observer = std::function<void(uint64_t t_ns, uint32_t y, bool level)>;
  static constexpr uint32_t kOutputs = 256;

  explicit OutputImage(const Memory& mem) : mem_(mem) {}

  void own(uint32_t y, bool owned);
  void observe(Observer f) { observers_.push_back(std::move(f)); }
  // Source s runs at hz while output y is ON, and stands still while it is OFF.
  void follow(uint32_t y, PulseSource* s, double hz) { followers_.push_back({y, s, hz}); }
  // The refresh of Y first ... first+n-1 at t.
  void refresh(uint32_t first, uint32_t n, uint64_t t_ns);
  // The scan's refresh of the whole image, which usually finds nothing changed: one pass
  // with no branch answers that, and only a change walks the image.
  void refresh_all(uint64_t t_ns) {
    if (!unchanged()) refresh(0, kOutputs, t_ns);
  }

 private:
  struct Follower {
    uint32_t y;
    PulseSource* src;
    double hz;
  };
  void changed(uint32_t y, bool v, uint64_t t_ns);
  bool unchanged() const;  // no output of ours differs from the terminals

  const Memory& mem_;
  // One byte per output, as the memory's: 1 ON; owned: 1 where the output is not ours.
  alignas(8) std::array<uint8_t, kOutputs> phys_{};
  alignas(8) std::array<uint8_t, kOutputs> owned_{};
  std::vector<Observer> observers_;
  std::vector<Follower> followers_;
};

}  // namespace hsc
}  // namespace plc_cell
