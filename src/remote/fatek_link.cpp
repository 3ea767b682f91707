#include "plc_cell/remote/fatek_link.h"

#include <algorithm>

#include "plc_cell/fatek/poll_plan.h"
#include "plc_cell/io/endpoint.h"

namespace plc_cell {
namespace remote {

FatekLink::FatekLink(const FatekLinkOptions& opt) {
  fatek::ClientOptions co;
  co.station = opt.station;
  co.timeout_ms = opt.timeout_ms;
  co.retries = opt.retries;
  std::unique_ptr<Transport> t = client_transport(opt.endpoint);  // the FBs' 9600 7E1 by default
  name_ = "FATEK " + t->describe() + " station " + std::to_string(opt.station);
  client_ = std::make_unique<fatek::Client>(std::move(t), co);
}

std::vector<uint32_t> FatekLink::read(const std::vector<Address>& addrs) {
  std::vector<fatek::PollItem> items;
  items.reserve(addrs.size());
  for (const Address& a : addrs) items.push_back({a, 1});
  const fatek::PollPlan plan = fatek::plan_poll(items);
  frames_ += plan.requests.size();
  const uint64_t retries = client_->retries_used();
  std::vector<std::vector<uint32_t>> got;
  try {
    got = fatek::run_poll(*client_, items, plan);
  } catch (...) {
    frames_ += client_->retries_used() - retries;
    throw;
  }
  frames_ += client_->retries_used() - retries;
  std::vector<uint32_t> out;
  out.reserve(got.size());
  for (const auto& v : got) out.push_back(v.at(0));
  return out;
}

std::optional<RunMode> FatekLink::mode() {
  ++frames_;
  return client_->status().run ? RunMode::Run : RunMode::Stop;
}

void FatekLink::write(const Address& start, const std::vector<uint32_t>& values) {
  ++frames_;
  client_->write(start, values);
}

namespace {

// Points of one area closer than this are read in one 43 frame with the points between:
// a frame's own bytes cost more than that many answer characters.
constexpr uint32_t kReadThrough = 16;

}  // namespace

std::optional<std::vector<bool>> FatekLink::forced(const std::vector<Address>& bits) {
  std::vector<bool> out(bits.size(), false);
  std::vector<size_t> order(bits.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return std::make_pair(bits[a].area, bits[a].index) < std::make_pair(bits[b].area, bits[b].index);
  });
  const uint64_t retries = client_->retries_used();
  try {
    for (size_t k = 0; k < order.size();) {
      const Address first = bits[order[k]];
      size_t end = k + 1;
      while (end < order.size() && bits[order[end]].area == first.area &&
             bits[order[end]].index - bits[order[end - 1]].index <= kReadThrough &&
             bits[order[end]].index - first.index < fatek::kMaxDiscretes)
        ++end;
      ++frames_;
      const uint32_t n = bits[order[end - 1]].index - first.index + 1;
      const std::vector<bool> run = client_->read_disabled(Address{first.area, Width::Bit, first.index}, n);
      for (size_t j = k; j < end; ++j) out[order[j]] = run.at(bits[order[j]].index - first.index);
      k = end;
    }
  } catch (...) {
    frames_ += client_->retries_used() - retries;
    throw;
  }
  frames_ += client_->retries_used() - retries;
  return out;
}

void FatekLink::force(const Address& bit, ForceAction action) {
  static const fatek::Action kActions[] = {fatek::Action::Disable, fatek::Action::Enable, fatek::Action::Set,
                                           fatek::Action::Reset};
  ++frames_;
  client_->control(bit, kActions[int(action)]);
}

}  // namespace remote
}  // namespace plc_cell
