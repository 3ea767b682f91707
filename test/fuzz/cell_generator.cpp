#include "cell_generator.h"

#include <algorithm>
#include <sstream>

#include "cell_part.h"

namespace plc_cell_fuzz {
namespace {

// EN/DIS of random interrupts from the ladder (the time bases are enabled through R4162).
void enable_and_disable(CellDraft& d) {
  Fdp& f = d.f;
  for (const std::string& l : d.labels) {
    if (l.find("MSI") != std::string::npos || l == "HSTAI" || !chance(f, 6)) continue;
    const bool en = f.ConsumeBool();
    d.body << "ORG M" << (f.ConsumeBool() ? 1925 : 710) << "\nFUN 14" << (en ? "5 EN" : "6 DIS") << " LBL=" << l << "\n";
  }
}

std::string yaml(CellDraft& d) {
  std::ostringstream y;
  y << "cell:\n  name: generated\n";
  static const int scans_ms[] = {1, 2, 5};
  const uint64_t scan_ms = static_cast<uint64_t>(pick(d.f, scans_ms));
  d.out.scan_us = scan_ms * 1000;
  d.out.span_us = d.out.scan_us * d.f.ConsumeIntegralInRange<uint64_t>(50, 300);
  y << "plc:\n  scan_period: " << scan_ms / 1000.0 << "\n";
  for (const auto& s : d.sections())
    if (!s.second.str().empty()) y << s.first << ":\n" << s.second.str();
  if (!d.sim.str().empty()) y << "simulation:\n  inputs:\n" << d.sim.str();
  return y.str();
}

std::string il(CellDraft& d) {
  std::ostringstream il;
  il << "ORG M1924\n" << d.init.str() << d.body.str() << "END\n";
  std::vector<std::string> labels = d.labels;
  std::sort(labels.begin(), labels.end());
  labels.erase(std::unique(labels.begin(), labels.end()), labels.end());
  int r = 600;
  for (const std::string& l : labels) il << "LBL " << l << "\nORG M1925\nINC D=R" << r++ << "\nRTI\n";
  return il.str();
}

}  // namespace

GeneratedCell generate_cell(FuzzedDataProvider& fdp) {
  CellDraft d(fdp);
  for (const CellPart& part : cell_parts()) part.generate(d);
  enable_and_disable(d);
  d.out.yaml = yaml(d);
  d.out.il = il(d);
  return d.out;
}

}  // namespace plc_cell_fuzz
