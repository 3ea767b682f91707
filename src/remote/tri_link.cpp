#include "plc_cell/remote/tri_link.h"

#include <cstdio>

#include "plc_cell/io/endpoint.h"
#include "plc_cell/tri/poll_plan.h"

namespace plc_cell {
namespace remote {

TriLink::TriLink(const TriLinkOptions& opt) {
  tri::ClientOptions co;
  co.id = opt.id;
  co.timeout_ms = opt.timeout_ms;
  co.retries = opt.retries;
  std::unique_ptr<Transport> t = client_transport(opt.endpoint, {"8N1", tri::kDefaultBaud});
  char id[8];
  std::snprintf(id, sizeof id, "%02X", unsigned(opt.id) & 0xFF);
  name_ = "TRi " + t->describe() + " ID " + id;
  client_ = std::make_unique<tri::Client>(std::move(t), co);
}

std::vector<uint32_t> TriLink::read(const std::vector<Address>& addrs) {
  std::vector<tri::PollItem> items;
  items.reserve(addrs.size());
  for (const Address& a : addrs) items.push_back({a, 1});
  const tri::PollPlan plan = tri::plan_poll(items);  // throws for an element not on a TRi
  const auto got = tri::run_poll(*client_, plan);
  std::vector<uint32_t> out;
  out.reserve(got.size());
  for (const auto& v : got) out.push_back(v.at(0));
  return out;
}

void TriLink::write(const Address& start, const std::vector<uint32_t>& values) {
  for (const tri::Request& r : tri::plan_write(start, values)) client_->transact(r);
}

std::string TriLink::no_forcing() const {
  return "the TRi has no DISABLE flag, so its host link cannot hold a point (write it instead)";
}

void TriLink::force(const Address& bit, ForceAction) { throw Error(format_address(bit) + ": " + no_forcing()); }

void TriLink::set_run(bool run) {
  tri::Request r;
  r.cmd = run ? tri::Cmd::Resume : tri::Cmd::Halt;
  client_->transact(r);
  mode_ = run ? RunMode::Run : RunMode::Stop;
}

}  // namespace remote
}  // namespace plc_cell
