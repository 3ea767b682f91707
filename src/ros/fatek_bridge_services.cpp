// fatek_bridge's side of plc_node's ~read, ~write, ~force and ~release (ros/memory_services.h):
// each request is one or a few FATEK transactions between two polls. Not offered:
// ~inputs/<name>, since a real PLC takes X from its terminals at every scan (a written X
// would last one scan); ~force holds an input instead.
#include "plc_cell/ros/fatek_bridge.h"

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"

namespace plc_cell {

Address FatekBridge::resolve(const std::string& text) const {
  for (const auto& s : signals_)
    if (s.first == text) return s.second;
  return parse_address(text);
}

std::vector<uint32_t> FatekBridge::read(const Address& start, uint32_t count) {
  check_span(start, count);  // before the link: a bad request costs no transaction
  std::lock_guard<std::mutex> lk(link_mu_);
  return client_->read(start, count);  // 44 (discretes) or 46 (registers)
}

void FatekBridge::write(const Address& start, const std::vector<uint32_t>& raw) {
  check_span(start, uint32_t(raw.size()));
  std::lock_guard<std::mutex> lk(link_mu_);
  client_->write(start, raw);
}

void FatekBridge::force(const Address& bit, bool value) {
  std::lock_guard<std::mutex> lk(link_mu_);
  // Command 42, lock first and then set, as plc_node does: the program cannot overwrite
  // the new state in between.
  client_->control(bit, fatek::Action::Disable);
  client_->control(bit, value ? fatek::Action::Set : fatek::Action::Reset);
}

std::vector<Address> FatekBridge::release(const Address* bit) {
  std::vector<Address> spans;  // starts of the ranges to look at, with their sizes
  std::vector<uint32_t> sizes;
  if (bit) {
    spans.push_back(*bit);
    sizes.push_back(1);
  } else {
    for (int ai = 0; ai < kAreaCount; ++ai) {
      const Area area = static_cast<Area>(ai);
      if (!is_discrete(area)) continue;
      spans.push_back(Address{area, Width::Bit, 0});
      sizes.push_back(area_size(area));
    }
  }
  std::vector<Address> freed;
  std::lock_guard<std::mutex> lk(link_mu_);
  for (size_t k = 0; k < spans.size(); ++k) {
    // Command 43 tells which points are locked, so only those get a 42 ENABLE and the
    // reply lists what was actually freed.
    const std::vector<bool> disabled = client_->read_disabled(spans[k], sizes[k]);
    for (uint32_t i = 0; i < disabled.size(); ++i) {
      if (!disabled[i]) continue;
      const Address p = offset_address(spans[k], i);
      client_->control(p, fatek::Action::Enable);
      freed.push_back(p);
    }
  }
  return freed;
}

}  // namespace plc_cell
