#include "plc_cell/online/change_service.h"

#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>

#include "plc_cell/config/online_check_facet.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/file_text.h"
#include "plc_cell/core/il_parser.h"
#include "plc_cell/core/online_change.h"
#include "plc_cell/online/child_process.h"
#include "plc_cell/online/il_diff.h"

namespace plc_cell {
namespace online {

namespace {

std::string base_name(const std::string& path) {
  const auto slash = path.rfind('/');
  return slash == std::string::npos ? path : path.substr(slash + 1);
}

double ms_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// The new program in a folder of its own, named as the running one (the reports' file:line).
class ScratchProgram {
 public:
  ScratchProgram(const std::string& name, const std::string& text) {
    char dir[] = "/tmp/plc_cell_gate.XXXXXX";
    if (!mkdtemp(dir)) throw Error(std::string("cannot make a folder for the gate: ") + std::strerror(errno));
    dir_ = dir;
    path_ = dir_ + "/" + name;
    std::ofstream f(path_, std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw Error("cannot write " + path_);
  }
  ~ScratchProgram() {
    std::remove(path_.c_str());
    rmdir(dir_.c_str());
  }
  const std::string& path() const { return path_; }

 private:
  std::string dir_, path_;
};

// What the gate's report says, in one line.
std::string summary_of(const nlohmann::json& report) {
  if (!report.is_object()) return "no report";
  return report.value("summary", std::string("no summary"));
}

}  // namespace

ChangeService::ChangeService(Plc& plc, ChangeSetup setup)
    : plc_(plc), setup_(std::move(setup)), log_(setup_.program_path) {
  text_ = file_text(setup_.program_path).value_or("");
  hash_ = text_hash(text_);
}

std::string ChangeService::text() const {
  std::lock_guard<std::mutex> lk(mu_);
  return text_;
}

std::pair<std::string, std::string> ChangeService::running_text() const {
  std::lock_guard<std::mutex> lk(mu_);
  return {text_, hash_};
}

std::string ChangeService::hash() const {
  std::lock_guard<std::mutex> lk(mu_);
  return hash_;
}

ChangeOutcome ChangeService::examine(const std::string& text, Program* program, bool* parsed) {
  ChangeOutcome o;
  o.result = "checked";
  o.new_hash = text_hash(text);
  std::string old_text;
  {
    std::lock_guard<std::mutex> lk(mu_);
    old_text = text_;
    o.old_hash = hash_;
  }
  const std::string name = base_name(setup_.program_path);
  o.diff = unified_diff(old_text, text, "a/" + name, "b/" + name);
  *parsed = false;
  try {
    *program = parse_program(text, setup_.program_path, plc_.functions());
    *parsed = true;
  } catch (const SourceError& e) {
    for (const auto& d : e.diagnostics())
      if (!d.warning) o.errors.push_back({d.where.line, d.where.column, d.message});
  } catch (const Error& e) {
    o.errors.push_back({0, 0, e.what()});
  }
  if (!*parsed) return o;
  o.instructions = static_cast<uint32_t>(program->code.size());
  o.refusals = plc_.locked([&](const ScanEngine& e, const Memory&) { return refusals_locked(e, *program); });
  return o;
}

ChangeOutcome ChangeService::check(const std::string& text) {
  Program p;
  bool parsed = false;
  ChangeOutcome o = examine(text, &p, &parsed);
  std::lock_guard<std::mutex> lk(gate_mu_);
  if (last_gate_.hash == o.new_hash && (!setup_.gate.mutate || last_gate_.since == o.old_hash)) o.gate = last_gate_;
  return o;
}

std::vector<std::string> ChangeService::refusals_locked(const ScanEngine& e, const Program& next) const {
  std::vector<std::string> out = online_change_refusals(e, next);
  if (e.mode() != RunMode::Run || !setup_.extensions) return out;
  for (const auto& x : *setup_.extensions)
    if (const auto* f = x->get<OnlineCheckFacet>())
      for (auto& why : f->refusals(e.program(), next)) out.push_back(std::move(why));
  return out;
}

GateResult ChangeService::test(const std::string& text) {
  const std::string hash = text_hash(text);
  GateResult g;
  g.hash = hash;
  g.configured = has_gate();
  if (!g.configured) {
    g.summary = "the cell names no gate (gate: in its YAML)";
    return g;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::string tool = setup_.tool.empty() ? tool_path() : setup_.tool;
  ChildResult r;
  if (tool.empty()) {
    r.failure = "the plc_cell tool is neither beside this program nor at $PLC_CELL_TOOL";
  } else {
    const ScratchProgram scratch(base_name(setup_.program_path), text);
    std::vector<std::string> argv = {tool, "gate", setup_.cell_file, "--program", scratch.path(), "--json"};
    // Mutation testing mutates the lines written since the running program: the verdict is
    // of this pair of texts.
    std::unique_ptr<ScratchProgram> since;
    if (setup_.gate.mutate) {
      const auto running = running_text();
      g.since = running.second;
      since = std::make_unique<ScratchProgram>(base_name(setup_.program_path), running.first);
      argv.insert(argv.end(), {"--since", since->path()});
    }
    r = run_child(argv, setup_.gate.timeout_us);
  }
  g.seconds = ms_since(t0) / 1000.0;
  g.report = nlohmann::json::parse(r.out, nullptr, false);
  if (!r.failure.empty()) {
    g.passed = false;
    g.summary = "the gate could not run: " + r.failure;
  } else if (r.timed_out) {
    g.passed = false;
    g.summary = "the gate took longer than gate.timeout (" + std::to_string(setup_.gate.timeout_us / 1000000) +
                " s) and was stopped";
  } else if (g.report.is_discarded() || !g.report.is_object()) {
    g.passed = false;
    g.summary = "the gate gave no report (exit " + std::to_string(r.exit_code) + "): " + r.err.substr(0, 2000);
    g.report = nullptr;
  } else {
    g.passed = r.exit_code == 0 && g.report.value("passed", false);
    g.summary = summary_of(g.report);
  }
  std::lock_guard<std::mutex> lk(gate_mu_);
  last_gate_ = g;
  return g;
}

GateResult ChangeService::gate_for(const std::string& text, const std::string& hash) {
  {
    const std::string running = running_text().second;
    std::lock_guard<std::mutex> lk(gate_mu_);
    if (last_gate_.hash == hash && last_gate_.configured == has_gate() &&
        (!setup_.gate.mutate || last_gate_.since == running))
      return last_gate_;
  }
  return test(text);
}

std::string ChangeService::compile_beside(const Program& program) const {
  const EngineChoice engine = plc_.locked([](const ScanEngine& e, const Memory&) { return e.engine(); });
  try {
    Plc scratch(plc_.functions());
    // The code generated for the new program without touching the running one; a lockstep
    // cell's twin is its own, so the scratch runs the native engine alone.
    scratch.locked([&](ScanEngine& e, Memory&) {
      e.set_engine(engine == EngineChoice::Lockstep ? EngineChoice::Native : engine);
      return 0;
    });
    scratch.load_program(program);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void ChangeService::rewrite_program_file(const std::string& text) const {
  const std::string tmp = setup_.program_path + ".tmp";
  {
    std::ofstream f(tmp, std::ios::binary);
    f << text;
    f.flush();
    if (!f) throw Error("cannot write " + tmp + ": " + std::strerror(errno));
  }
  if (std::rename(tmp.c_str(), setup_.program_path.c_str()) != 0)
    throw Error("cannot replace " + setup_.program_path + ": " + std::strerror(errno));
}

ChangeOutcome ChangeService::logged(ChangeOutcome o, const ChangeRequest& r) {
  try {
    log_.append(o, r.source, r.reason);
  } catch (const Error& e) {
    o.why += (o.why.empty() ? "" : "; ") + std::string(e.what());
  }
  return o;
}

// Refused at the first step that says no; the swap itself under the PLC lock, between two
// scans, with what may not change in RUN checked again right there.
ChangeOutcome ChangeService::apply_locked(const ChangeRequest& r, bool undo) {
  Program program;
  bool parsed = false;
  ChangeOutcome o = examine(r.text, &program, &parsed);
  o.undo = undo;
  o.result = "refused";
  if (!parsed) {
    o.why = "the program has " + std::to_string(o.errors.size()) + " error(s)";
    return logged(o, r);
  }
  if (o.new_hash == o.old_hash) {
    o.why = "this program is already running";
    return logged(o, r);
  }
  if (!o.refusals.empty()) {
    o.why = "a change in RUN may not do this: " + o.refusals.front();
    return logged(o, r);
  }
  if (const std::string why = compile_beside(program); !why.empty()) {
    o.why = "the new program cannot run: " + why;
    return logged(o, r);
  }
  o.gate = gate_for(r.text, o.new_hash);
  bool forced = false;
  if (o.gate.configured && !o.gate.passed) {
    if (!r.force) {
      o.why = "the gate failed: " + o.gate.summary;
      return logged(o, r);
    }
    if (r.reason.empty()) {
      o.why = "apply anyway needs a reason";
      return logged(o, r);
    }
    forced = true;
  }
  try {
    log_.keep_version(o.old_hash, text());
    log_.keep_version(o.new_hash, r.text);
    std::ofstream probe(log_.path(), std::ios::app);  // a change that cannot be logged is not made
    if (!probe) throw Error("cannot append to the change log " + log_.path() + ": " + std::strerror(errno));
  } catch (const Error& e) {
    o.why = e.what();
    return logged(o, r);
  }
  const auto t0 = std::chrono::steady_clock::now();
  o.refusals = plc_.locked([&](ScanEngine& e, Memory&) {
    std::vector<std::string> why = refusals_locked(e, program);  // the state may have moved on
    if (why.empty()) e.load_online(program);
    return why;
  });
  o.swap_ms = ms_since(t0);
  if (!o.refusals.empty()) {
    o.why = "a change in RUN may not do this: " + o.refusals.front();
    return logged(o, r);
  }
  {
    std::lock_guard<std::mutex> lk(mu_);
    text_ = r.text;
    hash_ = o.new_hash;
  }
  o.result = forced ? "forced" : "applied";
  if (r.source != ChangeSource::File) {
    try {
      rewrite_program_file(r.text);
    } catch (const Error& e) {
      o.why = std::string("applied, but the program file was not rewritten: ") + e.what();
    }
  }
  return logged(o, r);
}

ChangeOutcome ChangeService::apply(const ChangeRequest& request) {
  std::lock_guard<std::mutex> lk(apply_mu_);
  return apply_locked(request, false);
}

ChangeOutcome ChangeService::undo(ChangeSource source) {
  std::lock_guard<std::mutex> lk(apply_mu_);
  ChangeRequest r;
  r.source = source;
  r.reason = "undo";
  const auto target = log_.undo_target();
  const auto text = target ? log_.version(*target) : std::nullopt;
  if (!text) {
    ChangeOutcome o;
    o.result = "refused";
    o.undo = true;
    o.old_hash = hash();
    o.why = target ? "the program to go back to (" + *target + ") is not kept in " + setup_.program_path + ".versions"
                   : "no applied change to undo";
    return logged(o, r);
  }
  r.text = *text;
  return apply_locked(r, true);
}

}  // namespace online
}  // namespace plc_cell
