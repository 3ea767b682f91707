#pragma once
// The mutation run's report: the score per program and per network ("network 5 (line
// 31)": counted from 1, with the line of its first instruction, as coverage and the
// monitor count them), and every survivor and equivalent-suspect at file:line with why and
// the cases that executed it; as text, JSON (schema in docs/testing-your-cell.md) and an
// HTML section for the coverage page. All deterministic: the same results give the same
// bytes.
#include <ostream>
#include <string>
#include <vector>

#include "plc_cell/mutation/mutation_run.h"

namespace plc_cell {
namespace mutation {

// Why a mutant that passed every case survived, in this order: no case executed its line;
// executed, but no case saw an observed value differ (an input search did); a case saw a
// value differ, and no check failed.
enum class Survival { NotExecuted, NotObserved, NotChecked };
const char* survival_name(Survival s);  // "not executed", "not observed", "not checked"
Survival survival(const ProgramResult& p, const MutantResult& r);

struct Score {
  size_t killed = 0, survived = 0, equivalent = 0, not_loaded = 0;
  size_t not_executed = 0, not_observed = 0, not_checked = 0;  // the survivors by Survival
  // killed / (killed + survived): equivalent-suspects (no case and no input search tells
  // them apart) and mutants that do not load left out. None when nothing counts: a suite
  // that killed nothing of nothing has no score, not 100 %.
  bool has_score() const { return killed + survived > 0; }
  double score() const { return has_score() ? double(killed) / double(killed + survived) : 0.0; }
};

Score score(const ProgramResult& p);
// The network of a line (nullptr: none).
const NetworkSpan* network_of(const ProgramResult& p, int line);

void write_text(const std::vector<ProgramResult>& programs, std::ostream& out);
void write_json(const std::vector<ProgramResult>& programs, std::ostream& out);
std::string html_section(const std::vector<ProgramResult>& programs);

}  // namespace mutation
}  // namespace plc_cell
