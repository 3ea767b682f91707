#include "plc_cell/line/line_target.h"

namespace plc_cell {
namespace line {

LineTarget::LineTarget(const std::string& line_file, const std::vector<SettingOverride>& run)
    : LineTarget(load_line_file(line_file), run) {}

LineTarget::LineTarget(const LineFile& file, const std::vector<SettingOverride>& run) {
  LineOptions o;
  o.run = run;
  line_ = std::make_unique<Line>(file, o);
  line_->run();
  for (size_t i = 0; i < line_->size(); ++i) cells_.push_back(std::make_unique<scenario::CellTarget>(*line_->cell(i)));
}

LineTarget::~LineTarget() = default;

scenario::Target* LineTarget::target_of(const std::string& cell, std::string*) {
  const int i = line_->find(cell);
  return i < 0 ? nullptr : cells_[size_t(i)].get();
}

std::vector<scenario::Target*> LineTarget::cell_targets() {
  std::vector<scenario::Target*> out;
  for (auto& c : cells_) out.push_back(c.get());
  return out;
}

}  // namespace line
}  // namespace plc_cell
