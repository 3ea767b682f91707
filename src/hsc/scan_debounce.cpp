#include "plc_cell/hsc/scan_debounce.h"

namespace plc_cell {
namespace hsc {

bool ScanDebounce::sample(bool raw, uint64_t t) {
  if (!started_) {  // at RUN the present level is taken as settled
    started_ = true;
    stable_ = raw;
    pending_ = false;
    return stable_;
  }
  if (raw == stable_) {
    pending_ = false;  // the pulse ended before the filter time: lost
    return stable_;
  }
  if (!pending_) {
    pending_ = true;
    since_ = t;
  }
  if (t - since_ >= width_) {
    stable_ = raw;
    pending_ = false;
  }
  return stable_;
}

}  // namespace hsc
}  // namespace plc_cell
