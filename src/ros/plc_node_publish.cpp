// plc_node's own topics (~io, ~io_words, ~forced, ~signals/<name>, ~signals_stamped/<name>)
// and the topic groups, published after the scans whatever the driver: every message is
// stamped with the ROS time of the cell's scan it shows (ScanDriver::stamp), and the scan
// thread only reads what changed; the driver's post() says on which thread it goes out.
#include <std_msgs/Bool.h>

#include "plc_cell/ForcedPoints.h"
#include "plc_cell/IoState.h"
#include "plc_cell/IoWords.h"
#include "plc_cell/Signal.h"
#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

namespace {
// Bit b of word i is point 16 i + b, as in the W views.
void pack_words(const std::vector<uint8_t>& bits, IoWords::_x_type* words) {
  for (size_t i = 0; i < bits.size() && i / 16 < words->size(); ++i)
    if (bits[i]) (*words)[i / 16] |= static_cast<uint16_t>(1u << (i % 16));
}
}  // namespace

PlcNode::Snapshot PlcNode::take_snapshot(const ScanEngine& e, const Memory& m) const {
  Snapshot s;
  s.scan_us = e.now_us();
  s.run = e.mode() == RunMode::Run;
  s.x.resize(256);
  s.y.resize(256);
  for (uint32_t i = 0; i < 256; ++i) {
    s.x[i] = m.bit(Area::X, i);
    s.y[i] = m.bit(Area::Y, i);
  }
  for (const auto& sig : cell_->config().signals) s.signals.push_back(m.bit(sig.second.area, sig.second.index));
  s.forced_gen = m.disabled_generation();
  return s;
}

bool PlcNode::unchanged(const ScanEngine& e, const Memory& m, const Snapshot& seen) const {
  if ((e.mode() == RunMode::Run) != seen.run || m.disabled_generation() != seen.forced_gen) return false;
  const uint8_t* x = m.bits(Area::X);
  const uint8_t* y = m.bits(Area::Y);
  uint8_t diff = 0;  // no early exit: a branch-free loop over both images
  for (uint32_t i = 0; i < 256; ++i) diff |= static_cast<uint8_t>(((x[i] & kBitState) ^ seen.x[i]) | ((y[i] & kBitState) ^ seen.y[i]));
  if (diff) return false;
  size_t k = 0;
  for (const auto& sig : cell_->config().signals)
    if (m.bit(sig.second.area, sig.second.index) != static_cast<bool>(seen.signals[k++])) return false;
  return true;
}

// On the driver's scan thread: compare, and hand what is due to the driver's post(). The
// snapshot is copied only when it changed (or ~io is due again), not at every scan.
uint64_t PlcNode::scanned() {
  uint64_t cell_us = 0;
  std::unique_ptr<Snapshot> s = cell_->plc().locked([&](ScanEngine& e, Memory& m) {
    cell_us = e.now_us();
    return seen_any_ && unchanged(e, m, seen_) ? nullptr : std::make_unique<Snapshot>(take_snapshot(e, m));
  });
  const ros::Time stamp = driver_->stamp(cell_us);
  const uint64_t rate_us = stamp.toNSec() / 1000;  // the rates count in the stamps' time
  const bool again = driver_->republishes() && io_rate_->due(rate_us);
  if (!s && again) {
    s = std::make_unique<Snapshot>(seen_);
    s->scan_us = cell_us;
  }
  bool post = false;
  if (s) {
    seen_ = *s;
    seen_any_ = true;
    std::lock_guard<std::mutex> lk(shown_mu_);
    shown_->pending = std::move(*s);
    post = !shown_->posted;
    shown_->posted = true;
  }
  if (post) driver_->post([this] { publish_io(); });
  topic_groups_.after_scan(rate_us, every_scan_, stamp, [this](std::function<void()> fn) { driver_->post(std::move(fn)); });
  return cell_us;
}

void PlcNode::publish_io() {
  std::lock_guard<std::mutex> order(io_mu_);
  Snapshot s, prev;
  bool first;
  {
    std::lock_guard<std::mutex> lk(shown_mu_);
    s = shown_->pending;
    shown_->posted = false;
    prev = shown_->last;
    first = !shown_->published;
  }
  publish(s, prev, first);
  std::lock_guard<std::mutex> lk(shown_mu_);
  shown_->last = std::move(s);
  shown_->published = true;
}

void PlcNode::publish(const Snapshot& s, const Snapshot& prev, bool all_signals) {
  const ros::Time stamp = driver_->stamp(s.scan_us);
  IoState msg;
  msg.header.stamp = stamp;
  msg.header.frame_id = frame_id_;
  msg.run = s.run;
  msg.x.assign(s.x.begin(), s.x.end());
  msg.y.assign(s.y.begin(), s.y.end());
  io_pub_.publish(msg);
  IoWords words;
  words.header = msg.header;
  words.run = s.run;
  pack_words(s.x, &words.x);
  pack_words(s.y, &words.y);
  io_words_pub_.publish(words);
  std::vector<size_t> sent{0};  // ~io, as the counts of Shown number them
  if (all_signals || prev.forced_gen != s.forced_gen) {
    publish_forced(stamp);
    sent.push_back(1);
  }
  for (size_t i = 0; i < signal_pubs_.size() && i < s.signals.size(); ++i) {
    if (!all_signals && i < prev.signals.size() && prev.signals[i] == s.signals[i]) continue;
    std_msgs::Bool b;
    b.data = s.signals[i];
    signal_pubs_[i].publish(b);
    Signal st;
    st.header.stamp = stamp;
    st.header.frame_id = frame_id_;
    st.data = s.signals[i];
    stamped_pubs_[i].publish(st);
    sent.push_back(2 + i);
    sent.push_back(2 + signal_pubs_.size() + i);
  }
  std::lock_guard<std::mutex> lk(shown_mu_);
  for (size_t k : sent) ++shown_->counts[k];
}

// The forced set is read in one lock only when Memory says it changed (a few thousand
// flag bytes, once per force or release), so the scan never pays for it.
void PlcNode::publish_forced(const ros::Time& stamp) {
  ForcedPoints msg;
  msg.header.stamp = stamp;
  std::vector<std::pair<std::string, bool>> list = cell_->plc().locked([](ScanEngine&, Memory& m) {
    std::vector<std::pair<std::string, bool>> out;
    for (const Address& a : m.disabled_points()) out.emplace_back(format_address(a), m.bit(a.area, a.index));
    return out;
  });
  for (const auto& p : list) {
    msg.addresses.push_back(p.first);
    msg.states.push_back(p.second);
  }
  forced_pub_.publish(msg);
  std::lock_guard<std::mutex> lk(shown_mu_);
  shown_->forced = std::move(list);
}

// In the order ~virtual_time/scanned has always listed them: ~io, ~forced, the signals,
// the stamped signals, ~io_words (one with every ~io), then the groups'.
void PlcNode::count_published(std::vector<std::string>* topics, std::vector<uint64_t>* counts) {
  topics->push_back(io_pub_.getTopic());
  topics->push_back(forced_pub_.getTopic());
  for (const auto& p : signal_pubs_) topics->push_back(p.getTopic());
  for (const auto& p : stamped_pubs_) topics->push_back(p.getTopic());
  topics->push_back(io_words_pub_.getTopic());
  {
    std::lock_guard<std::mutex> lk(shown_mu_);
    counts->insert(counts->end(), shown_->counts.begin(), shown_->counts.end());
    counts->push_back(shown_->counts[0]);
  }
  topic_groups_.count_published(topics, counts);
}

}  // namespace plc_cell
