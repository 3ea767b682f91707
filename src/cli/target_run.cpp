// plc_cell test --target: the run. Everything is checked before anything is written: the
// files must allow the target, every step must be one the target can do, the PLC must be
// in RUN and every time window no tighter than the resolution measured on the link; then
// the cases run one after the other, each restored before the next (target_case.cpp).
#include "target_run.h"

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <iostream>

#include "scenario_files.h"
#include "target_context.h"
#include "plc_cell/hardware/target_spec.h"
#include "plc_cell/scenario/junit.h"
#include "plc_cell/scenario/wall_clock.h"
#include "plc_cell/scenario/wall_clock_target.h"

namespace plc_cell {
namespace cli {

namespace {



hardware::TargetOptions parse_target_options(const Args& args) {
  hardware::TargetOptions o;
  o.text = args.get("target");
  if (args.has("station")) o.station = int(args.get_int("station", 1, 0, 255));
  if (args.has("id")) o.id = int(args.get_int("id", 1, 0, 255));
  if (args.has("timeout")) {
    const uint64_t us = parse_duration_us(args.get("timeout"));
    if (us < 1000 || us > 60000000) throw UsageError("--timeout " + args.get("timeout") + ": out of range [1ms, 60s]");
    o.timeout_ms = int(us / 1000);
  }
  o.retries = int(args.get_int("retries", o.retries, 0, 10));
  return o;
}

// $XDG_STATE_HOME/plc_cell (else ~/.local/state/plc_cell): one journal per target.
std::string journal_path(const std::string& target) {
  const char* xdg = std::getenv("XDG_STATE_HOME");
  const char* home = std::getenv("HOME");
  std::string dir = xdg && *xdg ? xdg : std::string(home && *home ? home : "/tmp") + "/.local/state";
  dir += "/plc_cell";
  for (size_t at = dir.find('/', 1); at != std::string::npos; at = dir.find('/', at + 1))
    ::mkdir(dir.substr(0, at).c_str(), 0755);  // the folders above, as mkdir -p
  ::mkdir(dir.c_str(), 0755);
  std::string name = target;
  for (char& ch : name)
    if (!isalnum(static_cast<unsigned char>(ch)) && ch != '-' && ch != '.') ch = '_';
  return dir + "/restore-" + name + ".journal";
}

std::vector<FileRun> select_cases(const std::vector<scenario::Scenario>& files, const std::vector<std::string>& k) {
  std::vector<FileRun> runs;
  for (const auto& sc : files) {
    FileRun f;
    f.sc = &sc;
    CellOverrides o;
    o.program = sc.program;
    f.cell = std::make_unique<Cell>(sc.cell, o, Cell::Purpose::Check);
    for (const auto& c : sc.cases) {
      bool chosen = k.empty();
      for (const auto& name : k) chosen = chosen || c.name.find(name) != std::string::npos;
      if (chosen) f.cases.push_back(c);
    }
    if (!f.cases.empty()) runs.push_back(std::move(f));
  }
  return runs;
}

// "plc_cell test on FATEK ... (--target ...): forces X0 (start_button), ...; writes R0"
void print_banner(const TargetRun& run, const std::vector<FileRun>& runs) {
  std::vector<scenario::Case> all;
  for (const auto& f : runs) all.insert(all.end(), f.cases.begin(), f.cases.end());
  // The names resolve the same in every file's cell: the first one's is as good as any.
  std::cout << "plc_cell test on " << run.plc->describe() << " (--target " << run.target << "): "
            << scenario::forces_and_writes(all, runs.front().cell->config()) << "\n";
  std::cout << "between cases the PLC is not reset: each case starts where the one before left it, with what "
               "that one forced and wrote put back (a file's setup: brings it to a known state)\n";
  for (const auto& f : runs) {
    std::string played;
    for (const auto& s : f.cell->config().sim_inputs) played += (played.empty() ? "" : ", ") + s.name;
    if (!played.empty())
      std::cout << f.sc->file << ": the cell's simulation plays " << played
                << " in virtual time; on the PLC only the cases' steps drive them\n";
  }
}

// Every refusal of every file at once (scenario::refusals_on), file by file.
std::vector<Diagnostic> check_files(TargetRun& run, std::vector<FileRun>& runs,
                                    const scenario::WallClockRules& rules, std::vector<scenario::StepNote>* widened,
                                    bool connected) {
  std::vector<Diagnostic> errors;
  for (auto& f : runs) {
    const auto e = scenario::refusals_on(*run.plc, run.target, *f.sc, f.cell->config(), rules, &f.cases, widened,
                                         connected);
    errors.insert(errors.end(), e.begin(), e.end());
  }
  return errors;
}

int refused(const std::vector<Diagnostic>& errors, const char* nothing) {
  for (const auto& e : errors) std::cerr << e.to_string() << "\n";
  std::cerr << "plc_cell test: " << errors.size() << " refusal(s); no case ran, " << nothing << "\n";
  return 1;
}

void print_plan(const std::vector<FileRun>& runs) {
  for (const auto& f : runs)
    for (const auto& c : f.cases) {
      std::cout << "case " << f.sc->file << ": " << c.name << "\n";
      for (const auto& a : scenario::planned_actions(c, f.cell->config())) std::cout << "  " << a.to_string() << "\n";
      std::string back;
      for (const auto& p : scenario::touched_points(c, f.cell->config())) back += (back.empty() ? "" : ", ") + p.label;
      std::cout << "  then put back as found: " << (back.empty() ? std::string("nothing") : back) << "\n";
    }
}

// Connected (reading only): the resolution measured, then every refusal of every file at
// once (its permission, the steps, the windows against the resolution, the PLC's mode);
// only then is a journal an earlier run left behind put back.
int connect_and_check(TargetRun& run, std::vector<FileRun>& runs, uint64_t tolerance_us) {
  std::vector<Address> polled;
  uint64_t scan_us = 0;
  for (const auto& f : runs) {
    scan_us = std::max(scan_us, f.cell->scan_period_us());
    for (const auto& c : f.cases) {
      const scenario::WallClockTarget t(*run.plc, f.cell->config(), c, {});
      for (const Address& a : t.polled_addresses())
        if (std::find(polled.begin(), polled.end(), a) == polled.end()) polled.push_back(a);
    }
  }
  run.resolution = scenario::measure_resolution(*run.plc, polled, scan_us);
  scenario::WallClockRules rules{run.plc->describe(), run.plc->cannot_force(), run.resolution.us(), tolerance_us};
  std::vector<scenario::StepNote>& widened = run.widened;
  const auto errors = check_files(run, runs, rules, &widened, true);
  run.run_mode = run.plc->mode() == RunMode::Run;
  std::cout << "connected: " << (run.run_mode ? "the PLC is in RUN" : "RUN not required") << "; resolution "
            << run.resolution.text() << "\n";
  for (const auto& w : widened) std::cout << w.to_string() << "\n";
  if (!errors.empty()) return refused(errors, "nothing was written");
  return restore_left_journal(run) ? 0 : 1;
}

std::string widened_text(const std::vector<scenario::StepNote>& widened) {
  std::string s;
  for (const auto& w : widened) s += (s.empty() ? "" : "; ") + w.to_string();
  return s.empty() ? "none" : s;
}

void write_target_junit(const TargetRun& run, const std::vector<scenario::CaseResult>& results, bool as_found,
                        const std::string& path) {
  std::ofstream out(path);
  if (!out) throw Error("cannot write the JUnit file " + path);
  scenario::JUnitRun j;
  j.target = run.target;
  j.properties = {{"plc", run.plc->describe()},
                  {"resolution", run.resolution.text()},
                  {"windows widened", widened_text(run.widened)},
                  {"left as found", as_found ? "yes" : "no: see the failures"}};
  scenario::write_junit(results, out, j);
}

// The cases one after the other; the run stops at a signal, or when a case could not be
// put back (the next would start from a PLC not as found, and overwrite the journal).
int run_all(TargetRun& run, std::vector<FileRun>& runs, const Args& args) {
  std::vector<scenario::CaseResult> results;
  size_t failed = 0, not_restored = 0;
  uint64_t wall_us = 0;
  bool cut = false;
  for (auto& f : runs) {
    for (size_t i = 0; i < f.cases.size() && !cut; ++i) {
      const CaseRun r = run_case_on_target(run, f, f.cases[i]);
      failed += !r.result.passed;
      not_restored += r.restore.not_restored.size();
      wall_us += r.result.virtual_us;
      results.push_back(r.result);
      cut = r.stopped || !r.restore.complete();
    }
  }
  std::cout << "== " << results.size() - failed << " passed, " << failed << " failed on " << run.plc->describe()
            << " (resolution " << scenario::wall_time(run.resolution.us()) << ", " << scenario::wall_time(wall_us)
            << " of wall-clock time); ";
  if (!not_restored)
    std::cout << "the PLC is as it was found\n";
  else
    std::cout << "NOT as it was found: " << not_restored << " point(s) not put back (above); the next run on "
              << run.target << " puts them back first (" << run.journal << ")\n";
  if (run.stop->signal_number()) std::cout << "plc_cell test: " << run.why_stopped() << ": no case ran after it\n";
  if (cut && !run.stop->signal_number()) std::cout << "plc_cell test: no case ran after it\n";
  if (args.has("junit")) write_target_junit(run, results, !not_restored, args.get("junit"));
  return failed || not_restored || cut ? 1 : 0;
}

}  // namespace

const std::vector<std::string>& target_options() {
  static const std::vector<std::string> o = {"target", "station", "id", "tolerance", "timeout", "retries",
                                             "restore-timeout"};
  return o;
}

int cmd_test_on_target(const Args& args) {
  if (!args.has("target")) throw UsageError("--dry-run lists what a run on a PLC would write and force: give --target");
  for (const char* o : {"coverage", "coverage-json", "coverage-html", "mutate", "engine"})
    if (args.has(o)) throw UsageError(std::string("--") + o + " goes with a run in virtual time, not with --target");
  TargetRun run;
  run.stop = std::make_unique<StopSignal>();  // before any thread: a signal from here on ends the run cleanly
  std::cout << std::unitbuf;                   // each line as it comes: the user watches a PLC
  run.target = args.get("target");
  try {
    run.plc = hardware::open_target(parse_target_options(args));
  } catch (const Error& e) {
    throw UsageError(e.what());
  }
  const uint64_t tolerance_us = args.has("tolerance") ? parse_duration_us(args.get("tolerance")) : 0;
  if (args.has("restore-timeout"))
    run.restore_for = std::chrono::milliseconds(parse_duration_us(args.get("restore-timeout")) / 1000);
  run.record_dir = args.get("record");
  run.journal = journal_path(run.target);
  std::vector<scenario::Scenario> files;
  if (!load_scenarios(args.positional(), "plc_cell test", &files)) return 1;
  std::vector<FileRun> runs = select_cases(files, args.all("case"));
  if (runs.empty()) throw UsageError("no case matches -k");
  print_banner(run, runs);
  if (args.has("dry-run")) {
    const auto errors =
        check_files(run, runs, {run.plc->describe(), run.plc->cannot_force(), std::nullopt, 0}, nullptr, false);
    print_plan(runs);
    std::cout << "dry run: nothing was sent to the PLC; time windows are checked against the resolution once "
                 "connected\n";
    return errors.empty() ? 0 : refused(errors, "nothing was sent");
  }
  try {
    if (const int rc = connect_and_check(run, runs, tolerance_us)) return rc;
  } catch (const CommError& e) {
    std::cerr << "plc_cell test: cannot reach " << run.plc->describe() << ": " << e.what()
              << "; no case ran, nothing was written\n";
    return 1;
  }
  return run_all(run, runs, args);
}

}  // namespace cli
}  // namespace plc_cell
