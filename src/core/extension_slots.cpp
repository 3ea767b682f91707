#include "plc_cell/core/extension_slots.h"

#include <atomic>

namespace plc_cell {

size_t ExtensionSlots::next_index() {
  static std::atomic<size_t> next{0};
  return next++;
}

}  // namespace plc_cell
