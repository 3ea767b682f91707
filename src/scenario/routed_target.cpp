#include "plc_cell/scenario/routed_target.h"

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace scenario {

Target* RoutedTarget::cell_of(const Probe& p, std::string* why) {
  if (p.cell.empty()) {
    *why = "'" + p.text + "': a line's names start with their cell: CELL." + p.text + " (cells: " + cell_names() + ")";
    return nullptr;
  }
  std::string absent;
  if (Target* t = target_of(p.cell, &absent)) return t;
  *why = "'" + p.text + "': " +
         (absent.empty() ? "no cell '" + p.cell + "' in the line (" + cell_names() + ")" : absent);
  return nullptr;
}

Target& RoutedTarget::cell_or_throw(const Probe& p) {
  std::string why;
  Target* t = cell_of(p, &why);
  if (!t) throw Error(why);
  return *t;
}

std::string RoutedTarget::check(const Probe& p, bool writing) {
  std::string why;
  Target* t = cell_of(p, &why);
  if (!t) return why;
  why = t->check(p, writing);
  return why.empty() ? why : p.cell + ": " + why;
}

void RoutedTarget::release(const Probe* p) {
  if (p) return cell_or_throw(*p).release(p);
  for (Target* t : cell_targets()) t->release(nullptr);
}

void RoutedTarget::simulate(const Probe* p) {
  if (p) return cell_or_throw(*p).simulate(p);
  for (Target* t : cell_targets()) t->simulate(nullptr);
}

std::string RoutedTarget::label(const Probe& p) {
  std::string why;
  Target* t = cell_of(p, &why);
  if (!t) return p.text;
  const std::string l = t->label(p);
  return l == p.text ? l : p.cell + "." + l;
}

}  // namespace scenario
}  // namespace plc_cell
