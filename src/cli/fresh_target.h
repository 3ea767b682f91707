#pragma once
// What a case of plc_cell test, a run of explore or a mutant's case runs on: a fresh cell of
// the scenario's cell YAML, or a fresh line of its line file (docs/lines.md).
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/scan_engine.h"
#include "plc_cell/line/line_target.h"
#include "plc_cell/mutation/mutation_run.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/scenario.h"

namespace plc_cell {
namespace cli {

class FreshTarget {
 public:
  // Throws SourceError or Error as the cell or the line does.
  FreshTarget(const scenario::Scenario& sc, std::optional<EngineChoice> engine, const std::string& program = "",
              const std::string& replacement = "");

  scenario::Target& target() { return cell_ ? static_cast<scenario::Target&>(*cell_) : *line_; }
  bool is_line() const { return line_ != nullptr; }
  line::LineTarget* line() { return line_.get(); }
  // Every cell, with its name in the line ("" for a lone cell), in the line's order.
  const std::vector<std::pair<std::string, Cell*>>& cells() const { return cells_; }
  // After each scan of cell i of cells(), with its instant.
  void after_scan(std::function<void(size_t cell, uint64_t t_us)> f);
  // Every program the cells run, each once, in the cells' order.
  std::vector<std::string> programs() const;

 private:
  std::unique_ptr<scenario::CellTarget> cell_;
  std::unique_ptr<line::LineTarget> line_;
  std::vector<std::pair<std::string, Cell*>> cells_;
};

// The --engine asked for, as every cell's run setting.
std::vector<SettingOverride> engine_settings(std::optional<EngineChoice> engine);

// The mutation run's factory (mutation/mutation_run.h) over fresh targets.
mutation::TargetFactory mutation_targets(std::optional<EngineChoice> engine);

}  // namespace cli
}  // namespace plc_cell
