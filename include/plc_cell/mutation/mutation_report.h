#pragma once
// The mutation run's report: the score per program and per network, and every survivor
// and equivalent-suspect at file:line with the cases that executed it; as text, JSON
// (schema in docs/testing-your-cell.md) and an HTML section for the coverage page. All
// deterministic: the same results give the same bytes.
#include <ostream>
#include <string>
#include <vector>

#include "plc_cell/mutation/mutation_run.h"

namespace plc_cell {
namespace mutation {

struct Score {
  size_t killed = 0, survived = 0, equivalent = 0, not_loaded = 0;
  // killed / (killed + survived): equivalent-suspects and mutants that do not load left out.
  double score() const { return killed + survived ? double(killed) / double(killed + survived) : 1.0; }
};

Score score(const std::vector<MutantResult>& results);
// The network of a line (0: none).
uint32_t network_of(const ProgramResult& p, int line);

void write_text(const std::vector<ProgramResult>& programs, std::ostream& out);
void write_json(const std::vector<ProgramResult>& programs, std::ostream& out);
std::string html_section(const std::vector<ProgramResult>& programs);

}  // namespace mutation
}  // namespace plc_cell
