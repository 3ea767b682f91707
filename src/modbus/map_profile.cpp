#include "plc_cell/modbus/map_profile.h"

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace modbus {

const MapProfile& map_profile(const std::string& name) {
  for (const MapProfile* p : {&fbs_map_profile(), &tri_map_profile()})
    if (name == p->name()) return *p;
  throw Error("Modbus map '" + name + "': expected fbs (the FBs manual's) or tri (the TRi's Table 14.1)");
}

}  // namespace modbus
}  // namespace plc_cell
