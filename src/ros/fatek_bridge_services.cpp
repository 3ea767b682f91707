// fatek_bridge's services that plc_node has too (~read, ~force, ~release), each one or a
// few FATEK transactions between two polls. Not here: ~inputs/<name>, since a real PLC
// takes X from its terminals at every scan (a written X would last one scan); ~force
// holds an input instead.
#include "plc_cell/ros/fatek_bridge.h"

#include "plc_cell/core/area.h"
#include "plc_cell/core/error.h"

namespace plc_cell {

void FatekBridge::advertise_plc_services(ros::NodeHandle& pnh) {
  services_.push_back(pnh.advertiseService("read", &FatekBridge::on_read, this));
  services_.push_back(pnh.advertiseService("force", &FatekBridge::on_force, this));
  services_.push_back(pnh.advertiseService("release", &FatekBridge::on_release, this));
}

Address FatekBridge::resolve(const std::string& text) const {
  for (const auto& s : signals_)
    if (s.first == text) return s.second;
  return parse_address(text);
}

bool FatekBridge::on_read(ReadMemory::Request& req, ReadMemory::Response& res) {
  try {
    const Address a = resolve(req.address);
    const uint32_t count = req.count == 0 ? 1 : req.count;
    check_span(a, count);  // before the link: a bad request costs no transaction
    std::vector<uint32_t> v;
    {
      std::lock_guard<std::mutex> lk(link_mu_);
      v = client_->read(a, count);  // 44 (discretes) or 46 (registers)
    }
    res.values.assign(v.begin(), v.end());
    res.success = true;
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool FatekBridge::on_force(ForceDiscrete::Request& req, ForceDiscrete::Response& res) {
  try {
    const Address a = resolve(req.address);
    if (a.width != Width::Bit) throw Error("force " + req.address + ": only a single discrete can be forced");
    std::lock_guard<std::mutex> lk(link_mu_);
    // Command 42, lock first and then set, as plc_node does: the program cannot
    // overwrite the new state in between.
    client_->control(a, fatek::Action::Disable);
    client_->control(a, req.value ? fatek::Action::Set : fatek::Action::Reset);
    res.success = true;
    res.message = format_address(a) + " forced " + (req.value ? "ON" : "OFF");
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

bool FatekBridge::on_release(ReleaseDiscrete::Request& req, ReleaseDiscrete::Response& res) {
  try {
    std::vector<Address> spans;  // starts of the ranges to look at, with their sizes
    std::vector<uint32_t> sizes;
    if (req.address.empty()) {
      for (int ai = 0; ai < kAreaCount; ++ai) {
        const Area area = static_cast<Area>(ai);
        if (!is_discrete(area)) continue;
        spans.push_back(Address{area, Width::Bit, 0});
        sizes.push_back(area_size(area));
      }
    } else {
      const Address a = resolve(req.address);
      if (a.width != Width::Bit) throw Error("release " + req.address + ": only a single discrete can be forced");
      spans.push_back(a);
      sizes.push_back(1);
    }
    std::lock_guard<std::mutex> lk(link_mu_);
    for (size_t k = 0; k < spans.size(); ++k) {
      // Command 43 tells which points are locked, so only those get a 42 ENABLE and the
      // reply lists what was actually freed.
      const std::vector<bool> disabled = client_->read_disabled(spans[k], sizes[k]);
      for (uint32_t i = 0; i < disabled.size(); ++i) {
        if (!disabled[i]) continue;
        const Address p = offset_address(spans[k], i);
        client_->control(p, fatek::Action::Enable);
        res.released.push_back(format_address(p));
      }
    }
    res.success = true;
    res.message = res.released.empty() ? "nothing was forced" : std::to_string(res.released.size()) + " released";
  } catch (const std::exception& e) {
    res.success = false;
    res.message = e.what();
  }
  return true;
}

}  // namespace plc_cell
