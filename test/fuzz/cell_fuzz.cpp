// Whole-cell fuzzer. An input whose first byte is even is a generated cell: the rest of
// the bytes drive cell_generator.h (axes with every FUN141 field, homing before/on/beyond
// the DOG, counters in every mode, interrupts, modules with PID, FUN150/151), and the
// wired axes' invariants are checked (cell_invariants.h). Any other input is a cell as
// text, "<yaml>\n%%IL%%\n<il>\n%%RUN%%\n<bytes>", mutated from the examples/ seeds.
// Both are built the way `plc_cell sim` builds a cell (a Cell for simulation: the
// protocol functions with their ports, the servers made and not started; RUN, VirtualRun). A cell the builder rejects must throw with a message; a
// crash, sanitizer report, invariant violation or a virtual second slower than the budget
// is a finding.
#include <fuzzer/FuzzedDataProvider.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "cell_generator.h"
#include "cell_invariants.h"
#include "plc_cell/core/address.h"
#include "plc_cell/runtime/cell.h"
#include "plc_cell/sim/virtual_run.h"

namespace {

const std::string& scratch() {
  static const std::string dir = [] {
    std::string d = "/tmp/plc_cell_fuzz_cell_" + std::to_string(::getpid());
    (void)std::system(("mkdir -p '" + d + "'").c_str());
    return d;
  }();
  return dir;
}

void write(const std::string& path, const std::string& text) {
  std::ofstream f(path, std::ios::binary | std::ios::trunc);
  f << text;
}

// CPU time of this thread: a run the scheduler starves (a loaded machine, a niced
// campaign) is not a hang; only the work the cell makes the PLC do counts.
double thread_cpu_s() {
  timespec ts{};
  ::clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + double(ts.tv_nsec) * 1e-9;
}

// CPU time one virtual second may take (ASan+UBSan build); more is a hang.
double second_budget_s() {
  static const double b = [] {
    const char* e = std::getenv("PLC_CELL_FUZZ_SECOND_BUDGET_S");
    return e && *e ? std::atof(e) : 20.0;
  }();
  return b;
}

// Runs in 100 ms slices of virtual time so a slow second is caught while it happens.
void run_bounded(plc_cell::Plc& plc, uint64_t span_us, uint64_t scan_us) {
  plc_cell::VirtualRun run(plc, scan_us);
  const uint64_t slice_us = 100000;
  for (uint64_t done = 0; done < span_us; done += slice_us) {
    const double t0 = thread_cpu_s();
    run.run_for(std::min(slice_us, span_us - done));
    const double cpu = thread_cpu_s() - t0;
    if (cpu > second_budget_s() * slice_us / 1e6) {
      std::fprintf(stderr, "HANG: 100 ms of virtual time took %.3f s of CPU time\n", cpu);
      std::abort();
    }
  }
}

plc_cell::CellOverrides program(const std::string& path) {
  plc_cell::CellOverrides o;
  o.program = path;
  return o;
}

// The one place the target builds a cell, as `plc_cell sim` does (src/cli/sim_command.cpp).
struct BuiltCell {
  plc_cell::Cell cell;
  BuiltCell(const std::string& yaml, const std::string& il)
      : cell((write(scratch() + "/cell.yaml", yaml), write(scratch() + "/cell.il", il), scratch() + "/cell.yaml"),
             program(scratch() + "/cell.il"), plc_cell::Cell::Purpose::Simulate) {}
};

void run_text_cell(const std::string& yaml, const std::string& il, uint64_t span_us, uint64_t scan_us) {
  BuiltCell b(yaml, il);
  if (!b.cell.plc().set_mode(plc_cell::RunMode::Run)) return;
  run_bounded(b.cell.plc(), span_us, scan_us);
}

void run_generated(const plc_cell_fuzz::GeneratedCell& g) {
  BuiltCell b(g.yaml, g.il);
  plc_cell_fuzz::WiredAxisCheck check(b.cell.soft(), g.wired);
  if (!b.cell.plc().set_mode(plc_cell::RunMode::Run)) return;
  run_bounded(b.cell.plc(), g.span_us, g.scan_us);
  check.check_at_rest();
}

void rejected(const std::exception& e) {
  if (std::string(e.what()).empty()) std::abort();  // a rejection must say why
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 0 && data[0] % 2 == 0) {
    FuzzedDataProvider fdp(data + 1, size - 1);
    const plc_cell_fuzz::GeneratedCell g = plc_cell_fuzz::generate_cell(fdp);
    if (std::getenv("PLC_CELL_FUZZ_PRINT")) std::fprintf(stderr, "%s%%%%IL%%%%\n%s", g.yaml.c_str(), g.il.c_str());
    try {
      run_generated(g);
    } catch (const std::exception& e) {
      if (std::getenv("PLC_CELL_FUZZ_PRINT")) std::fprintf(stderr, "rejected: %s\n", e.what());
      rejected(e);
    }
    return 0;
  }
  const std::string in(reinterpret_cast<const char*>(data), size);
  const size_t il_at = in.find("\n%%IL%%\n");
  if (il_at == std::string::npos) return 0;
  const size_t run_at = in.find("\n%%RUN%%\n", il_at);
  const std::string yaml = in.substr(0, il_at);
  const std::string il = in.substr(il_at + 8, run_at == std::string::npos ? std::string::npos : run_at - il_at - 8);
  const std::string tail = run_at == std::string::npos ? std::string() : in.substr(run_at + 9);
  FuzzedDataProvider fdp(reinterpret_cast<const uint8_t*>(tail.data()), tail.size());
  // Short spans keep executions per second high: 50-300 scans of 1 ms.
  const uint64_t span_us = fdp.ConsumeIntegralInRange<uint64_t>(50, 300) * 1000;
  try {
    run_text_cell(yaml, il, span_us, 1000);
  } catch (const std::exception& e) {
    rejected(e);
  }
  return 0;
}
