#pragma once
// How long a master waits before it tries a lost link again (the Modbus bridge's lines,
// the FATEK bridge): min_s after the first failure, doubled after each further one up to
// max_s, back to min_s once a connection succeeds or an operator asks to recover. A dead
// device is retried often at first, when it is most likely a blip, and then rarely
// enough that the retries cost nothing.
#include <algorithm>

namespace plc_cell {

class Backoff {
 public:
  Backoff(double min_s, double max_s) : min_s_(min_s), max_s_(max_s) {}

  // A connection attempt failed: the delay before the next one, in seconds.
  double failed() {
    delay_s_ = delay_s_ == 0 ? min_s_ : std::min(delay_s_ * 2, max_s_);
    return delay_s_;
  }
  // Connected (or told to recover): the next failure waits min_s again.
  void reset() { delay_s_ = 0; }

 private:
  double min_s_, max_s_;
  double delay_s_ = 0;  // the last delay given; 0 after a success
};

}  // namespace plc_cell
