#include "plc_cell/line/line_target.h"

#include "plc_cell/core/error.h"

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

scenario::CellTarget* LineTarget::cell_of(const scenario::Probe& p, std::string* why) {
  if (p.cell.empty()) {
    *why = "'" + p.text + "': a line's names start with their cell: CELL." + p.text + " (cells: " + line_->names() + ")";
    return nullptr;
  }
  const int i = line_->find(p.cell);
  if (i < 0) {
    *why = "'" + p.text + "': no cell '" + p.cell + "' in the line (" + line_->names() + ")";
    return nullptr;
  }
  return cells_[size_t(i)].get();
}

scenario::CellTarget& LineTarget::cell_or_throw(const scenario::Probe& p) {
  std::string why;
  scenario::CellTarget* t = cell_of(p, &why);
  if (!t) throw Error(why);
  return *t;
}

std::string LineTarget::check(const scenario::Probe& p, bool writing) {
  std::string why;
  scenario::CellTarget* t = cell_of(p, &why);
  if (!t) return why;
  why = t->check(p, writing);
  return why.empty() ? why : p.cell + ": " + why;
}

scenario::Reading LineTarget::read(const scenario::Probe& p) { return cell_or_throw(p).read(p); }
void LineTarget::set(const scenario::Probe& p, const scenario::Value& v) { cell_or_throw(p).set(p, v); }
void LineTarget::write(const scenario::Probe& p, const scenario::Value& v) { cell_or_throw(p).write(p, v); }
void LineTarget::force(const scenario::Probe& p, bool on) { cell_or_throw(p).force(p, on); }

void LineTarget::release(const scenario::Probe* p) {
  if (p) return cell_or_throw(*p).release(p);
  for (auto& c : cells_) c->release(nullptr);
}

void LineTarget::simulate(const scenario::Probe* p) {
  if (p) return cell_or_throw(*p).simulate(p);
  for (auto& c : cells_) c->simulate(nullptr);
}

std::string LineTarget::label(const scenario::Probe& p) {
  std::string why;
  scenario::CellTarget* t = cell_of(p, &why);
  if (!t) return p.text;
  const std::string l = t->label(p);
  return l == p.text ? l : p.cell + "." + l;
}

}  // namespace line
}  // namespace plc_cell
