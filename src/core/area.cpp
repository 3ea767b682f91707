#include "plc_cell/core/area.h"

namespace plc_cell {

uint32_t area_size(Area a) {
  switch (a) {
    case Area::X: return 256;
    case Area::Y: return 256;
    case Area::M: return 2002;
    case Area::S: return 1000;
    case Area::T: return 256;
    case Area::C: return 256;
    case Area::RT: return 256;
    case Area::RC: return kCounterCount;
    case Area::R: return 8072;
    case Area::D: return 4096;
    case Area::F: return 8192;
  }
  return 0;
}

const char* area_name(Area a) {
  static const char* const names[] = {"X", "Y", "M", "S", "T", "C", "RT", "RC", "R", "D", "F"};
  return names[static_cast<int>(a)];
}

}  // namespace plc_cell
