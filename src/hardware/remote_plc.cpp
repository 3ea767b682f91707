#include "plc_cell/hardware/remote_plc.h"

#include "plc_cell/remote/fatek_link.h"
#include "plc_cell/remote/tri_link.h"
#include "plc_cell/tri/poll_plan.h"

namespace plc_cell {
namespace hardware {

RemotePlc::RemotePlc(std::unique_ptr<remote::Link> link, std::function<std::string(const Address&)> reach,
                     std::string no_mode)
    : link_(std::move(link)), reach_(std::move(reach)), no_mode_(std::move(no_mode)) {}

void RemotePlc::force(const Address& bit, bool on) {
  link_->force(bit, ForceAction::Disable);
  link_->force(bit, on ? ForceAction::Set : ForceAction::Reset);
}

std::optional<RunMode> RemotePlc::mode() {
  // The TRi link answers with what it last set itself: nothing a scenario may trust.
  if (!no_mode_.empty()) return std::nullopt;
  return link_->mode();
}

std::unique_ptr<scenario::LinkedPlc> open_fatek(const std::string& endpoint, int station, int timeout_ms, int retries) {
  remote::FatekLinkOptions o;
  o.endpoint = endpoint;
  o.station = station;
  o.timeout_ms = timeout_ms;
  o.retries = retries;
  // Every address of the FBs memory map goes on the wire; a smaller PLC answers 'A'.
  return std::make_unique<RemotePlc>(std::make_unique<remote::FatekLink>(o), [](const Address&) { return ""; }, "");
}

std::unique_ptr<scenario::LinkedPlc> open_tri(const std::string& endpoint, int id, int timeout_ms, int retries) {
  remote::TriLinkOptions o;
  o.endpoint = endpoint;
  o.id = id;
  o.timeout_ms = timeout_ms;
  o.retries = retries;
  auto reach = [](const Address& a) -> std::string {
    try {
      tri::check_on_tri(a, 1);
      return "";
    } catch (const Error& e) {
      return e.what();
    }
  };
  return std::make_unique<RemotePlc>(std::make_unique<remote::TriLink>(o), reach,
                                     "the TRi's host link does not report RUN or STOP");
}

}  // namespace hardware
}  // namespace plc_cell
