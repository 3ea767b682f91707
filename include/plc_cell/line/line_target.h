#pragma once
// A line of cells as a scenario target (`plc_cell test` and `plc_cell explore` of a file
// that names a line: docs/lines.md, "Tests across cells"): the whole line is one target,
// each of whose scans is one instant of the line's clock (its tick: the greatest common
// divisor of the cells' periods), at which every cell due scans. Every name is CELL.NAME,
// read and driven in that cell as a lone cell's target would (scenario/cell_target.h).
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/line/line.h"
#include "plc_cell/scenario/cell_target.h"
#include "plc_cell/scenario/routed_target.h"

namespace plc_cell {
namespace line {

class LineTarget : public scenario::RoutedTarget {
 public:
  // Throws SourceError (the line's, its cells' or programs' errors) or Error. Every cell is
  // put in RUN. run: the front end's run settings for every cell (--engine).
  explicit LineTarget(const std::string& line_file, const std::vector<SettingOverride>& run = {});
  LineTarget(const LineFile& file, const std::vector<SettingOverride>& run);
  ~LineTarget() override;

  Line& line() { return *line_; }

  uint64_t period_us() const override { return line_->tick_us(); }
  void scan(uint64_t t_us) override { line_->scan_at(t_us); }
  std::string fault() override { return line_->fault(); }

 private:
  scenario::Target* target_of(const std::string& cell, std::string* absent) override;
  std::string cell_names() const override { return line_->names(); }
  std::vector<scenario::Target*> cell_targets() override;

  std::unique_ptr<Line> line_;
  std::vector<std::unique_ptr<scenario::CellTarget>> cells_;  // each borrows a cell of line_
};

}  // namespace line
}  // namespace plc_cell
