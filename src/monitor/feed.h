#pragma once
// What one page asked to see (its subscription) and the frames that show it: one read of
// every address its networks and watch list need, at one instant, and the power flow of
// its networks from that frame and the one before.
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladder_view.h"

namespace plc_cell {
namespace monitor {

constexpr size_t kMaxWatch = 512;
constexpr int kDefaultRateHz = 10;

// A signal name of the program view or an address; throws Error naming text and why.
Address resolve(const std::string& text, const ProgramView& program);

struct Subscription {
  std::vector<size_t> networks;
  std::vector<std::string> watch;  // as the page wrote them (the frame's keys)
  std::vector<Address> watched;    // resolved, one per watch entry
  int rate_hz = kDefaultRateHz;
};

// {"subscribe": {"networks": [...], "watch": [...], "rate_hz": N}}; throws Error naming the
// field at fault and why.
Subscription parse_subscription(const nlohmann::json& message, const LadderView& ladder);

class Feed {
 public:
  Feed(Subscription s, std::shared_ptr<const LadderView> ladder);
  const Subscription& subscription() const { return sub_; }
  // {"type":"frame", ...}; Source::read errors propagate.
  nlohmann::json frame(Source& source);

 private:
  static uint64_t key(const Address& a);
  Subscription sub_;
  std::shared_ptr<const LadderView> ladder_;
  std::vector<Address> reads_;           // every distinct address, read in one frame
  std::map<uint64_t, size_t> slot_;      // address key -> index in reads_
  std::vector<uint32_t> prev_;           // the last frame's values (empty before the first)
};

}  // namespace monitor
}  // namespace plc_cell
