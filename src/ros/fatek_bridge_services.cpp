// fatek_bridge's side of plc_node's ~read, ~write, ~force and ~release, and ~read_forced
// (ros/memory_services.h):
// each request is one or a few FATEK transactions the bus side runs between two polls. Not
// offered: ~inputs/<name>, since a real PLC takes X from its terminals at every scan (a
// written X would last one scan); ~force holds an input instead.
#include "plc_cell/ros/fatek_bridge.h"

namespace plc_cell {

Address FatekBridge::resolve(const std::string& text) const { return bridge_->resolve(text); }

std::vector<uint32_t> FatekBridge::read(const Address& start, uint32_t count) { return bridge_->read(start, count); }

void FatekBridge::write(const Address& start, const std::vector<uint32_t>& raw) { bridge_->write(start, raw); }

void FatekBridge::force(const Address& bit, bool value) { bridge_->force(bit, value); }

std::vector<Address> FatekBridge::release(const Address* bit) { return bridge_->release(bit); }

std::vector<bool> FatekBridge::forced(const std::vector<Address>& bits) { return bridge_->forced(bits); }

}  // namespace plc_cell
