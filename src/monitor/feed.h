#pragma once
// What one page asked to see (its subscription) and the frames that show it: one read of
// every address its networks and watch list need, at one instant, and the power flow of
// its networks from that frame and the one before. A frame draws power flow only from
// values of a scanning cell: in STOP no network runs, and values that could not be read
// again (a link that is down) are shown as the last ones read, marked stale with their age.
#include <chrono>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "ladder_view.h"
#include "plc_cell/monitor/source_set.h"

namespace plc_cell {
namespace monitor {

constexpr size_t kMaxWatch = 512;
constexpr int kDefaultRateHz = 10;

// A signal name of the program view or an address; throws Error naming text and why.
Address resolve(const std::string& text, const ProgramView& program);

// "infeed.X3" on cell infeed's page (of a line's set) is its X3; any other text as it is.
std::string own_name(const std::string& text, const SourceSet* set, size_t self);

struct Subscription {
  std::vector<size_t> networks;
  std::vector<std::string> watch;  // as the page wrote them (the frame's keys)
  std::vector<Address> watched;    // resolved, one per watch entry
  // Watch entries qualified by another cell of the set (robot.X3): read from that cell.
  std::vector<std::pair<std::string, Located>> elsewhere;
  const SourceSet* set = nullptr;
  int rate_hz = kDefaultRateHz;
};

// {"subscribe": {"networks": [...], "watch": [...], "rate_hz": N}}; throws Error naming the
// field at fault and why. set, self: the cells the page's cell is served with, and which
// one it is (qualified names of the others are theirs).
Subscription parse_subscription(const nlohmann::json& message, const LadderView& ladder,
                                const SourceSet* set = nullptr, size_t self = 0);

class Feed {
 public:
  // before: the page's previous subscription, whose last values stand in while the source
  // cannot be read.
  Feed(Subscription s, std::shared_ptr<const LadderView> ladder, const Feed* before = nullptr);
  const Subscription& subscription() const { return sub_; }
  // {"type":"frame", ...}. A read that fails gives a stale frame (the error in it).
  nlohmann::json frame(Source& source);
  // Why the last frame's read failed ("" when it read).
  const std::string& failure() const { return failure_; }

 private:
  struct Known {
    uint32_t value = 0;
    bool forced = false;
  };
  static uint64_t key(const Address& a);
  nlohmann::json stale_frame(const std::string& why);
  void add_values(nlohmann::json& j, const std::vector<uint32_t>& values, const std::vector<uint8_t>& forced) const;
  void add_elsewhere(nlohmann::json& j) const;
  Subscription sub_;
  std::shared_ptr<const LadderView> ladder_;
  std::vector<Address> reads_;           // every distinct address, read in one frame
  std::map<uint64_t, size_t> slot_;      // address key -> index in reads_
  std::vector<uint32_t> prev_;           // the last frame's values (empty before the first)
  // The last values read, by address key, and when: what a stale frame shows.
  std::map<uint64_t, Known> known_;
  std::chrono::steady_clock::time_point known_at_;
  uint64_t known_scan_ = 0, known_t_us_ = 0;
  bool have_known_ = false;
  std::string failure_;
};

}  // namespace monitor
}  // namespace plc_cell
