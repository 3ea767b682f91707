#include "plc_cell/config/probe_facet.h"

#include <cstdio>

#include "plc_cell/core/error.h"

namespace plc_cell {

void ProbeFacet::drive(Plc&, const ProbeRef& p, const ProbeInput&) const {
  throw Error(p.text + ": only an address or signal is written");
}

std::string probe_number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

}  // namespace plc_cell
