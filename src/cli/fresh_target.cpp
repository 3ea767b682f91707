#include "fresh_target.h"

#include <filesystem>

#include "plc_cell/config/cell_config.h"

namespace plc_cell {
namespace cli {

namespace {

// One spelling per file, whatever path led to it.
std::string same_file(const std::string& path) {
  std::error_code ec;
  const auto p = std::filesystem::weakly_canonical(path, ec);
  return ec ? path : p.string();
}

// The line file with program replaced by replacement in every cell that runs it.
line::LineFile replaced(const std::string& path, const std::string& program, const std::string& replacement) {
  line::LineFile f = line::load_line_file(path);
  if (replacement.empty()) return f;
  const std::string target = same_file(program);
  for (auto& c : f.cells) {
    const std::string runs = c.program.empty() ? load_cell_config(c.config, Cell::sections()).program : c.program;
    if (same_file(runs) == target) c.program = replacement;
  }
  return f;
}

}  // namespace

std::vector<SettingOverride> engine_settings(std::optional<EngineChoice> engine) {
  std::vector<SettingOverride> run;
  if (engine) run.push_back({"", "engine", {engine_choice_name(*engine)}, "--engine"});
  return run;
}

FreshTarget::FreshTarget(const scenario::Scenario& sc, std::optional<EngineChoice> engine, const std::string& program,
                         const std::string& replacement) {
  const auto run = engine_settings(engine);
  if (sc.line.empty()) {
    const std::string p = !replacement.empty() ? replacement : !program.empty() ? program : sc.program;
    cell_ = std::make_unique<scenario::CellTarget>(sc.cell, p, run);
    cells_.push_back({"", &cell_->cell()});
    return;
  }
  line_ = std::make_unique<line::LineTarget>(replaced(sc.line, program, replacement), run);
  line::Line& l = line_->line();
  for (size_t i = 0; i < l.size(); ++i) cells_.push_back({l.entry(i).name, l.cell(i)});
}

void FreshTarget::after_scan(std::function<void(size_t, uint64_t)> f) {
  if (line_) return line_->line().after_scan(std::move(f));
  cell_->after_scan([f](uint64_t t) { f(0, t); });
}

std::vector<std::string> FreshTarget::programs() const {
  std::vector<std::string> out;
  for (const auto& c : cells_) {
    const std::string& p = c.second->program_path();
    bool seen = false;
    for (const auto& o : out) seen = seen || same_file(o) == same_file(p);
    if (!seen) out.push_back(p);
  }
  return out;
}

mutation::TargetFactory mutation_targets(std::optional<EngineChoice> engine) {
  return [engine](const scenario::Scenario& sc, const std::string& program, const std::string& replacement) {
    auto fresh = std::make_shared<FreshTarget>(sc, engine, program, replacement);
    mutation::Subject s;
    s.target = &fresh->target();
    s.programs = fresh->programs();
    const std::string under_test = same_file(program.empty() ? s.programs.front() : program);
    const std::string now_runs = same_file(replacement.empty() ? under_test : replacement);
    for (const auto& c : fresh->cells())
      if (same_file(c.second->program_path()) == now_runs)
        s.cells.push_back({c.second, c.first.empty() ? "" : c.first + "."});
    s.owner = fresh;
    return s;
  };
}

}  // namespace cli
}  // namespace plc_cell
