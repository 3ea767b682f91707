#include "plc_cell/persist/persister.h"

#include <algorithm>
#include <chrono>

#include "plc_cell/core/error.h"
#include "plc_cell/persist/retentive_image.h"

namespace plc_cell {
namespace persist {

Persister::Persister(Plc& plc, const PersistSettings& settings, std::function<void(const std::string&)> log)
    : plc_(plc), settings_(settings), log_(std::move(log)) {
  if (settings_.file.empty()) throw Error("persist: no store file given");
  if (!log_) log_ = [](const std::string&) {};
  const std::string live_path = settings_.file + ".live";
  std::vector<Slot> slots = read_slots(settings_.file, &problems_);
  for (auto& s : read_slots(live_path, &problems_)) slots.push_back(std::move(s));
  std::sort(slots.begin(), slots.end(), [](const Slot& a, const Slot& b) { return a.seq > b.seq; });
  // Every slot is checked whole before any byte of it reaches memory: the newest slot that
  // passes wins, and a damaged one (even with a valid CRC) contributes nothing.
  const Slot* chosen = nullptr;
  std::vector<StoredRange> stored;
  for (const auto& s : slots) {
    try {
      stored = parse_retentive(s.payload);
      chosen = &s;
      break;
    } catch (const Error& err) {
      problems_.push_back(s.where + ": " + err.what() + " (valid CRC, unusable layout)");
    }
  }
  for (const auto& p : problems_) log_("persist: " + p);

  plc_.locked([&](ScanEngine& e, Memory& m) {
    if (chosen) {
      std::vector<AreaRange> what;
      const size_t n = apply_retentive(chosen->payload, stored, e.retentive(), &m, &what);
      restored_ = "restored " + std::to_string(n) + " retentive elements (" +
                  (what.empty() ? std::string("none of the stored ranges is retentive now") : describe_ranges(what)) +
                  ") from " + chosen->where + " (sequence " + std::to_string(chosen->seq) + ")";
      if (!problems_.empty()) restored_ += "; fell back past " + std::to_string(problems_.size()) + " damaged slot(s)";
      seq_ = chosen->seq;
    } else if (problems_.empty()) {
      restored_ = "nothing restored: no stored image in " + settings_.file + " or " + live_path +
                  ": retentive ranges start cleared";
    } else {
      restored_ = "nothing restored: no stored image in " + settings_.file + " or " + live_path + " passed its checks (" +
                  std::to_string(problems_.size()) + " damaged slot(s)): retentive ranges start cleared";
    }
    encode_retentive(e.retentive(), m, &latest_);
    scratch_ = latest_;
    ++seq_;
    // Fresh files in the current layout, each replaced atomically.
    durable_ = std::make_unique<SlotFile>(settings_.file, seq_, latest_);
    live_ = std::make_unique<SlotFile>(live_path, seq_, latest_);
    durable_seq_ = seq_;
    engine_ = &e;
    memory_ = &m;
    e.add_hook(this);
    return 0;
  });
  log_("persist: " + restored_);
  plc_.set_durability(this);
  thread_ = std::thread([this] { flusher(); });
}

Persister::~Persister() {
  plc_.set_durability(nullptr);
  plc_.locked([&](ScanEngine& e, Memory&) {
    e.remove_hook(this);
    return 0;
  });
  {
    std::lock_guard<std::mutex> lk(mu_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

uint64_t Persister::capture(const ScanEngine& e, const Memory& m) { return capture_locked(e, m); }

// Called under the Plc lock (scan or client write): cheap when nothing retentive changed.
uint64_t Persister::capture_locked(const ScanEngine& e, const Memory& m) {
  encode_retentive(e.retentive(), m, &scratch_);
  std::lock_guard<std::mutex> lk(mu_);
  if (scratch_ == latest_) return seq_;
  if (scratch_.size() != latest_.size()) {
    error_ = "retentive ranges changed while running; persistence stopped";
    return seq_;
  }
  latest_.swap(scratch_);
  ++seq_;
  try {
    live_->write(seq_, latest_, false);  // in the page cache: survives the process
  } catch (const Error& err) {
    error_ = err.what();
  }
  return seq_;
}

// Inside Plc::scan, lock held: what the program latched in this scan reaches the live file.
void Persister::after_program(uint64_t) { capture_locked(*engine_, *memory_); }

void Persister::wait(uint64_t ticket) {
  if (!settings_.sync_writes) return;
  std::unique_lock<std::mutex> lk(mu_);
  wanted_ = std::max(wanted_, ticket);
  cv_.notify_all();
  // On an I/O error the write is acknowledged anyway (it is in memory and the live file);
  // the error shows in status() and on /diagnostics.
  cv_.wait(lk, [&] { return durable_seq_ >= ticket || stop_ || !error_.empty(); });
}

void Persister::flush_once(std::unique_lock<std::mutex>& lk) {
  const uint64_t seq = seq_;
  const std::vector<uint8_t> image = latest_;
  lk.unlock();
  std::string err;
  try {
    durable_->write(seq, image, true);
  } catch (const Error& e) {
    err = e.what();
  }
  lk.lock();
  if (err.empty()) {
    durable_seq_ = std::max(durable_seq_, seq);
    ++flushes_;
    if (flush_failed_) error_.clear();
    flush_failed_ = false;
  } else if (error_ != err) {
    error_ = err;
    flush_failed_ = true;
    log_("persist: " + err);
  }
  cv_.notify_all();
}

void Persister::flusher() {
  std::unique_lock<std::mutex> lk(mu_);
  const auto interval = std::chrono::microseconds(settings_.interval_us);
  auto next = std::chrono::steady_clock::now() + interval;
  while (!stop_) {
    cv_.wait_until(lk, next, [&] { return stop_ || (wanted_ > durable_seq_ && error_.empty()); });
    if (seq_ > durable_seq_) flush_once(lk);
    if (std::chrono::steady_clock::now() >= next) next = std::chrono::steady_clock::now() + interval;
  }
  if (seq_ > durable_seq_) flush_once(lk);  // a clean stop leaves the newest image on disk
}

PersistStatus Persister::status() const {
  std::lock_guard<std::mutex> lk(mu_);
  PersistStatus s;
  s.file = settings_.file;
  s.seq = seq_;
  s.durable_seq = durable_seq_;
  s.flushes = flushes_;
  s.restored = restored_;
  s.problems = problems_;
  s.error = error_;
  return s;
}

}  // namespace persist
}  // namespace plc_cell
