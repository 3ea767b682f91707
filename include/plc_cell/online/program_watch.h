#pragma once
// `plc_cell run --watch-program`: the program file polled, and a saved change handed to the
// change service as a change from the file (gated, checked and logged like any other; the
// file itself is never rewritten for it).
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

#include "plc_cell/config/program_changes.h"

namespace plc_cell {
namespace online {

class ProgramWatch {
 public:
  // report gets each outcome (the tool prints it). Polls every period_us.
  ProgramWatch(ProgramChanges& changes, std::function<void(const ChangeOutcome&)> report,
               uint64_t period_us = 200'000);
  ~ProgramWatch();
  // One look at the file now (what the thread does every period): true when it handed a
  // change over. A text that equals the running program, or the last one refused, is none.
  bool poll();

 private:
  ProgramChanges& changes_;
  std::function<void(const ChangeOutcome&)> report_;
  std::string last_refused_;  // the hash of the last text refused: tried again once saved anew
  std::mutex mu_;
  std::condition_variable cv_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace online
}  // namespace plc_cell
