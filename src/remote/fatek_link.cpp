#include "plc_cell/remote/fatek_link.h"

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

void FatekLink::force(const Address& bit, ForceAction action) {
  static const fatek::Action kActions[] = {fatek::Action::Disable, fatek::Action::Enable, fatek::Action::Set,
                                           fatek::Action::Reset};
  ++frames_;
  client_->control(bit, kActions[int(action)]);
}

}  // namespace remote
}  // namespace plc_cell
