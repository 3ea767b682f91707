#include "plc_cell/mutation/mutation_run.h"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "plc_cell/core/error.h"
#include "plc_cell/coverage/recorders.h"
#include "plc_cell/coverage/report.h"
#include "plc_cell/scenario/runner.h"
#include "input_search.h"
#include "tracing_target.h"

namespace plc_cell {
namespace mutation {

const char* verdict_name(Verdict v) {
  switch (v) {
    case Verdict::Killed: return "killed";
    case Verdict::Survived: return "survived";
    case Verdict::Equivalent: return "equivalent-suspect";
    case Verdict::NotLoaded: return "not loaded";
  }
  return "?";
}

namespace {

struct CaseRef {
  const scenario::Scenario* sc;
  const scenario::Case* c;
  uint64_t hash = 0;  // the original program's trace
};

// The cases of one program, in the order of the files and their cases, and the program as
// the cells parse it.
struct ProgramCases {
  std::string file;
  std::vector<CaseRef> cases;
  plc_cell::Program parsed;
  FunctionTable functions;
  // The outputs, the cell's signals, every case's probes, every element the program writes.
  std::vector<scenario::Probe> observed;
};

std::vector<std::string> lines_of(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw Error("mutation: cannot read the program " + path);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

// Every program a file's target runs (a line's: each of its cells'), with the file's cases.
std::vector<ProgramCases> programs(const std::vector<scenario::Scenario>& files, const TargetFactory& make) {
  std::vector<ProgramCases> out;
  for (const auto& sc : files) {
    if (sc.cases.empty()) continue;  // none selected: nothing could kill a mutant
    for (const std::string& file : make(sc, "", "").programs) {
      auto it = out.begin();
      while (it != out.end() && it->file != file) ++it;
      if (it == out.end()) it = out.insert(out.end(), ProgramCases{file, {}, {}, {}, {}});
      for (const auto& c : sc.cases) it->cases.push_back({&sc, &c});
    }
  }
  return out;
}

void observe(std::vector<scenario::Probe>* observed, const scenario::Probe& p) {
  for (const auto& o : *observed)
    if (o.text == p.text) return;
  observed->push_back(p);
}

// The lines a case executed: every instruction that recorded a value, every one of a
// network whose ORG ran (a network runs through: ANDLD, ORLD and M1925's contacts record
// nothing of their own), and a FOR (which records nothing) run into from the instruction
// before it or whose body ran.
void add_executed(const coverage::Recorder& rec, const std::string& name, ProgramResult* r) {
  const coverage::Report rep = coverage::report(rec);
  const plc_cell::Program& prog = rec.program();
  std::vector<bool> ran(prog.code.size(), false);
  for (size_t i = 0; i < prog.code.size(); ++i) {
    const int line = prog.code[i].line;
    ran[i] = rec.seen()[i] != 0;
    for (const auto& n : rep.networks) ran[i] = ran[i] || (n.evaluated && line >= n.line && line <= n.end_line);
  }
  for (size_t i = 0; i < prog.code.size(); ++i)
    if (prog.code[i].op == Op::For)
      ran[i] = ran[i] || (i > 0 && ran[i - 1] && prog.code[i - 1].op != Op::Jmp) ||
               (i + 1 < prog.code.size() && ran[i + 1]);
  for (size_t i = 0; i < prog.code.size(); ++i) {
    const int line = prog.code[i].line;
    if (!ran[i]) continue;
    auto& by = r->executed_by[line];
    if (by.empty() || by.back() != name) by.push_back(name);
  }
  if (r->networks.empty())
    for (const auto& n : rep.networks) r->networks.push_back({n.number, n.line, n.end_line});
}

// The original program: every case must pass; its traces, the lines each case executed.
void baseline(ProgramCases& p, const TargetFactory& make, ProgramResult* r) {
  for (auto& cr : p.cases) {
    const Subject s = make(*cr.sc, p.file, "");
    coverage::Recorders recs;
    coverage::Recorder* rec = nullptr;
    for (const auto& part : s.cells) rec = &recs.attach(part.cell->plc(), part.cell->config().signals);
    const std::vector<scenario::Probe> outputs = output_words(s);
    TracingTarget t(*s.target, *cr.c, outputs);
    const scenario::CaseResult res = scenario::run_case(*cr.c, t);
    for (const auto& part : s.cells) recs.detach(part.cell->plc());
    if (!res.passed)
      throw Error("mutation testing needs every case to pass on the original program: " + cr.c->name + ": " +
                  res.failure);
    cr.hash = t.hash();
    add_executed(*rec, cr.c->name, r);
    if (p.parsed.code.empty()) {
      p.parsed = rec->program();
      p.functions = s.cells.front().cell->plc().functions();
    }
    for (const auto& o : outputs) observe(&p.observed, o);
    for (const auto& part : s.cells)
      for (const auto& sig : part.cell->config().signals) observe(&p.observed, probe_of(part, sig.first));
    for (const auto& probe : case_probes(*cr.c)) observe(&p.observed, probe);
  }
}

// The file whose cell the search runs: the first with an explore: section, else the first.
const scenario::Scenario& search_file(const ProgramCases& p) {
  for (const auto& cr : p.cases)
    if (cr.sc->explore.line) return *cr.sc;
  return *p.cases.front().sc;
}

MutantResult run_mutant(const ProgramCases& p, const std::vector<std::string>& lines, const Mutant& m,
                        const std::string& path, const TargetFactory& make, InputSearch& search) {
  MutantResult r;
  r.mutant = m;
  std::ofstream(path, std::ios::trunc) << apply(lines, m);
  bool same = true;
  for (const auto& cr : p.cases) {
    Subject s;
    try {
      s = make(*cr.sc, p.file, path);
    } catch (const std::exception& e) {
      r.verdict = Verdict::NotLoaded;  // the parser refuses it: no program to test
      return r;
    }
    TracingTarget t(*s.target, *cr.c, output_words(s));
    if (!scenario::run_case(*cr.c, t).passed) {
      r.verdict = Verdict::Killed;
      r.killed_by = cr.c->name;
      return r;
    }
    same = same && t.hash() == cr.hash;
  }
  r.verdict = Verdict::Survived;
  r.observed = !same;
  if (r.observed) return r;
  const Finding f = search.tell_apart(path, m.line);
  if (f.found) {
    r.told_apart = f.text();
  } else {
    r.verdict = Verdict::Equivalent;
    r.searched = search.plan(m.line);
  }
  return r;
}

// A result through a pipe: its index, then each field as its length and its bytes.
std::string encode(size_t i, const MutantResult& r) {
  std::string o = std::to_string(i) + " " + std::to_string(int(r.verdict)) + " " + (r.observed ? "1" : "0");
  for (const std::string* f : {&r.killed_by, &r.told_apart, &r.searched}) o += " " + std::to_string(f->size()) + ":" + *f;
  return o + "\n";
}

// Decodes the results of one worker's output into results.
void decode(const std::string& in, std::vector<MutantResult>& results) {
  std::istringstream s(in);
  size_t i;
  int v, observed;
  while (s >> i >> v >> observed) {
    MutantResult& r = results.at(i);
    r.verdict = Verdict(v);
    r.observed = observed != 0;
    for (std::string* f : {&r.killed_by, &r.told_apart, &r.searched}) {
      size_t n;
      char colon;
      s >> n >> colon;
      f->assign(n, '\0');
      s.read(&(*f)[0], std::streamsize(n));
    }
  }
}

// The mutants split over jobs worker processes (mutant i to worker i % jobs); results in
// mutant order, whichever worker finished first.
void run_all(const ProgramCases& p, const std::vector<std::string>& lines, const Options& o,
             const TargetFactory& make, InputSearch& search, std::vector<MutantResult>& results) {
  char dir[] = "/tmp/plc_cell_mutants_XXXXXX";
  if (!mkdtemp(dir)) throw Error("mutation: cannot make a temporary folder");
  const int jobs = std::max(1, o.jobs);
  std::vector<std::pair<pid_t, int>> workers;
  std::fflush(nullptr);
  for (int w = 0; w < jobs; ++w) {
    int fd[2];
    if (pipe(fd) != 0) throw Error("mutation: cannot make a pipe");
    const pid_t pid = fork();
    if (pid < 0) throw Error("mutation: cannot start a worker process");
    if (pid == 0) {
      close(fd[0]);
      const std::string path = std::string(dir) + "/mutant" + std::to_string(w) + ".il";
      try {
        for (size_t i = size_t(w); i < results.size(); i += size_t(jobs)) {
          const std::string line = encode(i, run_mutant(p, lines, results[i].mutant, path, make, search));
          if (write(fd[1], line.data(), line.size()) < 0) _exit(2);
        }
      } catch (const std::exception& e) {
        std::fprintf(stderr, "mutation: %s\n", e.what());
        _exit(3);
      }
      _exit(0);
    }
    close(fd[1]);
    workers.push_back({pid, fd[0]});
  }
  for (const auto& [pid, fd] : workers) {
    std::string in;
    char buf[4096];
    for (ssize_t n; (n = read(fd, buf, sizeof buf)) > 0;) in.append(buf, size_t(n));
    close(fd);
    int status = 0;
    waitpid(pid, &status, 0);
    decode(in, results);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw Error("mutation: a worker process failed");
  }
  for (int w = 0; w < jobs; ++w) std::remove((std::string(dir) + "/mutant" + std::to_string(w) + ".il").c_str());
  rmdir(dir);
}

}  // namespace

std::vector<ProgramResult> run_mutation(const std::vector<scenario::Scenario>& files, const Options& options,
                                        const TargetFactory& make) {
  std::vector<ProgramResult> out;
  for (ProgramCases& p : programs(files, make)) {
    ProgramResult r;
    r.program = p.file;
    r.cases = p.cases.size();
    baseline(p, make, &r);
    const std::vector<std::string> lines = lines_of(p.file);
    std::vector<Mutant> all = mutants(lines, p.parsed, p.functions);
    if (!options.lines.empty())
      all.erase(std::remove_if(all.begin(), all.end(), [&](const Mutant& m) { return !options.lines.count(m.line); }),
                all.end());
    r.generated = all.size();
    const size_t n = options.budget && options.budget < all.size() ? options.budget : all.size();
    for (size_t i = 0; i < n; ++i) r.results.push_back({all[i * all.size() / n], Verdict::Survived, "", false, "", ""});
    // What a master or an HMI reads of the program's doing: every element it writes, in
    // each cell that runs it.
    const Subject s = make(*p.cases.front().sc, p.file, "");
    for (const Address& a : written_by(p.parsed, p.functions))
      for (const auto& part : s.cells) observe(&p.observed, probe_of(part, format_address(a)));
    InputSearch search(search_file(p), p.file, p.parsed, p.functions, p.observed, make);
    run_all(p, lines, options, make, search, r.results);
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace mutation
}  // namespace plc_cell
