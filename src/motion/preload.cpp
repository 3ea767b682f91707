// The YAML's FUN140/FUN141/FUN147 images written at RUN.
#include "plc_cell/motion/preload.h"

#include <vector>

#include "plc_cell/core/memory.h"

namespace plc_cell {
namespace motion {

namespace {
// Words at `at` on, as many as the area holds.
void put(Memory& mem, const Address& at, const uint16_t* w, size_t count) {
  for (size_t i = 0; i < count && at.index + i < Memory::word_count(at.area); ++i)
    mem.set_reg(at.area, static_cast<uint32_t>(at.index + i), w[i]);
}
}  // namespace

void preload_tables(Memory& mem, const AxesConfig& cfg) {
  for (size_t n = 0; n < cfg.axes.size(); ++n) {
    const AxisDef& a = cfg.axes[n];
    if (a.has_table) {
      const std::vector<uint16_t> r = encode_table(a.table);
      put(mem, a.table_at, r.data(), r.size());
    }
    if (a.params_image) {
      uint16_t r[kParamWords];
      a.params.to_registers(r);
      put(mem, a.params_at, r, kParamWords);
    }
  }
  for (const auto& g : cfg.groups)  // FUN147 tables (axes: gp0/gp1)
    if (g.has_table) {
      const std::vector<uint16_t> r = encode_lin_table(g.table);
      put(mem, g.table_at, r.data(), r.size());
    }
}

}  // namespace motion
}  // namespace plc_cell
