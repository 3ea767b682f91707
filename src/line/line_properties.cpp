#include "plc_cell/line/line_properties.h"

namespace plc_cell {
namespace line {

void watch_properties(Line& l, std::shared_ptr<scenario::PropertyWatcher> watcher) {
  // One buffer per cell: a cell's scans come one at a time, on its thread or a shared one.
  auto buffers = std::make_shared<std::vector<std::vector<uint32_t>>>(l.size());
  for (size_t i = 0; i < l.size(); ++i) (*buffers)[i].resize(watcher->addresses(i).size());
  l.after_scan([&l, watcher, buffers](size_t i, uint64_t t_us) {
    std::vector<uint32_t>& values = (*buffers)[i];
    if (!values.empty()) {
      const std::vector<Address>& at = watcher->addresses(i);
      l.cell(i)->plc().locked([&](ScanEngine&, Memory& m) {
        for (size_t k = 0; k < at.size(); ++k) values[k] = m.read(at[k]);
        return 0;
      });
    }
    watcher->scanned(i, t_us, values.data());
  });
}

}  // namespace line
}  // namespace plc_cell
