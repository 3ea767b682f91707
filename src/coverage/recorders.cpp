#include "plc_cell/coverage/recorders.h"

#include "plc_cell/core/error.h"

namespace plc_cell {
namespace coverage {

Recorder& Recorders::attach(Plc& plc, const SignalNames& names) {
  const std::string file = plc.locked([](ScanEngine& e, Memory&) { return e.program().file; });
  Recorder& r = by_file_[file];
  try {
    r.attach(plc, names);
  } catch (const Error&) {
    if (r.empty()) by_file_.erase(file);  // a PLC with no program leaves no empty recorder behind
    throw;
  }
  return r;
}

void Recorders::detach(Plc& plc) {
  for (auto& entry : by_file_) entry.second.detach(plc);
}

std::vector<Report> Recorders::reports() const {
  std::vector<Report> out;
  for (const auto& entry : by_file_) out.push_back(report(entry.second));
  return out;
}

}  // namespace coverage
}  // namespace plc_cell
