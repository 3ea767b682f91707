#include "plc_cell/online/program_watch.h"

#include <chrono>

#include "plc_cell/core/file_text.h"
#include "plc_cell/online/il_diff.h"

namespace plc_cell {
namespace online {

ProgramWatch::ProgramWatch(ProgramChanges& changes, std::function<void(const ChangeOutcome&)> report,
                           uint64_t period_us)
    : changes_(changes), report_(std::move(report)) {
  thread_ = std::thread([this, period_us] {
    std::unique_lock<std::mutex> lk(mu_);
    while (!cv_.wait_for(lk, std::chrono::microseconds(period_us), [this] { return stop_; })) {
      lk.unlock();
      poll();
      lk.lock();
    }
  });
}

ProgramWatch::~ProgramWatch() {
  {
    std::lock_guard<std::mutex> lk(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

bool ProgramWatch::poll() {
  const std::optional<std::string> read = file_text(changes_.file());
  if (!read) return false;  // an editor replacing the file: the next look sees the new one
  const std::string& text = *read;
  const std::string hash = text_hash(text);
  if (hash == changes_.hash() || hash == last_refused_) return false;
  ChangeRequest r;
  r.text = text;
  r.source = ChangeSource::File;
  const ChangeOutcome o = changes_.apply(r);
  last_refused_ = o.result == "refused" ? hash : "";
  if (report_) report_(o);
  return true;
}

}  // namespace online
}  // namespace plc_cell
