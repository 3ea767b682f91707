#include "plc_cell/sim/virtual_run.h"

namespace plc_cell {

size_t VirtualRun::watch(const Address& a) {
  watches_.push_back(a);
  last_.push_back(0);
  seen_.push_back(false);
  return watches_.size() - 1;
}

void VirtualRun::run_for(uint64_t duration_us, const std::function<void(const WatchChange&)>& on_change) {
  const uint64_t end = now_us_ + duration_us;
  while (now_us_ < end) {
    plc_.locked([&](ScanEngine& e, Memory& m) {
      e.scan(now_us_);
      for (size_t i = 0; i < watches_.size(); ++i) {
        const uint32_t v = m.read(watches_[i]);
        if (!seen_[i] || v != last_[i]) {
          seen_[i] = true;
          last_[i] = v;
          if (on_change) on_change({now_us_, i, v});
        }
      }
      return 0;
    });
    ++scans_;
    now_us_ += period_us_;
  }
}

std::vector<uint32_t> VirtualRun::values() const {
  return plc_.locked([&](const ScanEngine&, const Memory& m) {
    std::vector<uint32_t> v;
    for (const auto& a : watches_) v.push_back(m.read(a));
    return v;
  });
}

}  // namespace plc_cell
