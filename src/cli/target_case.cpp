// One case of `plc_cell test --target`: the points it will touch read (and journaled), the
// case run on the PLC by polling, and every point put back whatever happened.
#include <time.h>
#include <unistd.h>

#include <iostream>

#include "record_option.h"
#include "scenario_files.h"
#include "target_context.h"
#include "plc_cell/hardware/polled_recording.h"
#include "plc_cell/scenario/wall_clock_target.h"

namespace plc_cell {
namespace cli {

namespace {

using Micros = std::chrono::microseconds;

std::string seconds_text(std::chrono::milliseconds d) { return scenario::wall_time(uint64_t(d.count()) * 1000); }

// The case's recording of its polls, when --record asks for one.
std::unique_ptr<hardware::PolledRecording> polled_recording(TargetRun& run, const FileRun& file,
                                                            const scenario::Case& c, size_t addresses) {
  recording::RecordingInfo info = recording_info(*file.cell, "plc_cell test --target " + run.target + " " +
                                                                  file.sc->file + ": " + c.name);
  info.scan_period_us = run.resolution.period_us;
  return std::make_unique<hardware::PolledRecording>(info, run.plc->describe(), addresses, run.resolution.period_us,
                                                     run.run_mode);
}

scenario::RestoreOptions restore_options(TargetRun& run, StopSignal& give_up) {
  scenario::RestoreOptions o;
  o.retry_for = run.restore_for;
  o.wait = [&give_up](std::chrono::milliseconds d) { return give_up.wait_for(d); };
  o.waiting = [&run](const std::string& why) {
    std::cout << "    restore: the link is down (" << why << "); trying again until it is back, for up to "
              << seconds_text(run.restore_for) << " (Ctrl-C to give up)\n";
  };
  return o;
}

void print_restore(const scenario::RestoreResult& r) {
  if (!r.restored.empty()) {
    std::cout << "    restored as found:";
    for (const auto& p : r.restored) std::cout << "\n      " << p;
    std::cout << "\n";
  }
  for (const auto& p : r.not_restored) std::cout << "    NOT RESTORED: " << p << "\n";
}

}  // namespace

std::string TargetRun::why_stopped() const {
  return std::string("stopped by ") + (stop && stop->signal_number() ? stop->signal_name() : "a signal");
}

bool wait_or_stop(StopSignal& stop, Micros d) {
  const auto end = std::chrono::steady_clock::now() + d;
  for (;;) {
    const auto left = std::chrono::duration_cast<Micros>(end - std::chrono::steady_clock::now());
    if (left <= Micros(0)) return stop.wait_for(std::chrono::milliseconds(0));
    if (left >= std::chrono::milliseconds(1)) {
      if (stop.wait_for(std::chrono::duration_cast<std::chrono::milliseconds>(left))) return true;
      continue;
    }
    const timespec ts{0, long(left.count()) * 1000};
    ::nanosleep(&ts, nullptr);
  }
}

CaseRun run_case_on_target(TargetRun& run, const FileRun& file, const scenario::Case& c) {
  scenario::RestoreJournal journal(run.journal);
  scenario::WallClockOptions o;
  o.period_us = run.resolution.period_us;
  o.wait = [&run](Micros d) { return wait_or_stop(*run.stop, d); };
  o.why_stopped = [&run] { return run.why_stopped(); };
  o.journal = &journal;
  o.target_text = run.target;
  std::unique_ptr<hardware::PolledRecording> rec;
  if (!run.record_dir.empty())
    o.polled = [&](uint64_t t, const std::vector<Address>& a, const std::vector<uint32_t>& v) {
      if (!rec) rec = polled_recording(run, file, c, a.size());
      rec->polled(t, a, v);
    };
  scenario::WallClockTarget target(*run.plc, file.cell->config(), c, o);
  CaseRun out;
  out.result = scenario::begin_and_run(c, target);
  out.polls = target.polls();
  out.slowest_us = target.slowest_poll_us();
  out.touched = target.touched().size();
  out.stopped = run.stop->signal_number() != 0;
  if (rec) {
    const std::string path = save_case(rec->recorder(), out.result, run.record_dir, &run.recorded);
    if (!out.result.passed) out.result.details += "  recorded: " + monitor_command_for(path) + "\n";
  }
  print_result(*file.sc, out.result,
               scenario::wall_time(out.result.virtual_us) + ", " + std::to_string(out.polls) + " polls");
  if (out.slowest_us > run.resolution.us())
    std::cout << "    the slowest poll took " << scenario::wall_time(out.slowest_us) << ", longer than the resolution "
              << scenario::wall_time(run.resolution.us()) << ": an instant near a window's edge may be off by that much\n";
  if (out.touched) {
    StopSignal again;  // a signal from here on gives up waiting for a lost link
    out.restore = scenario::restore_points(*run.plc, target.found(), target.touched(), restore_options(run, again));
  }
  if (out.restore.complete()) journal.remove();
  print_restore(out.restore);
  if (!out.restore.complete()) {
    std::cout << "    the case counts as failed: the PLC is not as it found it\n";
    for (const auto& n : out.restore.not_restored) out.result.details += "  NOT RESTORED: " + n + "\n";
    out.result.passed = false;
  }
  return out;
}

bool restore_left_journal(TargetRun& run) {
  const auto left = scenario::RestoreJournal::load(run.journal);
  if (!left) return true;
  std::cout << "a run on " << left->target << " stopped before it put back what case '" << left->case_name
            << "' touched (" << run.journal << "): putting it back first\n";
  StopSignal again;
  const scenario::RestoreResult r = scenario::restore_points(*run.plc, left->found, left->touched,
                                                             restore_options(run, again));
  print_restore(r);
  if (!r.complete()) {
    std::cout << "plc_cell test: the PLC is not as that run found it: no case runs (the journal stays)\n";
    return false;
  }
  ::unlink(run.journal.c_str());
  return true;
}

}  // namespace cli
}  // namespace plc_cell
