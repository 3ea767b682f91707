#include "plc_cell/ros/extension_diagnostics.h"

#include <algorithm>

namespace plc_cell {
namespace {

unsigned char level_of(ExtensionStatus::Level l) {
  switch (l) {
    case ExtensionStatus::Level::Ok: return diagnostic_msgs::DiagnosticStatus::OK;
    case ExtensionStatus::Level::Warn: return diagnostic_msgs::DiagnosticStatus::WARN;
    case ExtensionStatus::Level::Error: break;
  }
  return diagnostic_msgs::DiagnosticStatus::ERROR;
}

void diagnose(const CellExtension& x, Plc& plc, diagnostic_updater::DiagnosticStatusWrapper& stat) {
  unsigned char level = diagnostic_msgs::DiagnosticStatus::OK;
  std::string message;
  const auto all = x.status(plc);
  for (const auto& s : all) {
    level = std::max(level, level_of(s.level));
    message += (message.empty() ? "" : "; ") + (all.size() > 1 ? s.name + ": " : "") + s.message;
    for (const auto& kv : s.values) stat.add(all.size() > 1 ? s.name + " " + kv.first : kv.first, kv.second);
  }
  stat.summary(level, message);
}

}  // namespace

std::vector<std::string> add_extension_diagnostics(diagnostic_updater::Updater& updater, SoftCell& cell) {
  std::vector<std::string> names;
  Plc& plc = cell.plc();
  for (const auto& x : cell.extensions()) {
    if (x->status(plc).empty()) continue;  // nothing configured that it would report on
    const CellExtension* ext = x.get();
    updater.add(ext->name(), [ext, &plc](diagnostic_updater::DiagnosticStatusWrapper& s) { diagnose(*ext, plc, s); });
    names.push_back(ext->name());
  }
  return names;
}

}  // namespace plc_cell
