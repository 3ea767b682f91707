// Whole-cell fuzzer: one input is a cell (YAML), its IL program and the virtual span to run,
// built through the path `plc_cell sim` takes (SoftCell, then VirtualRun). The input layout
// is "<yaml>\n%%IL%%\n<il>\n%%RUN%%\n<bytes>": seeds are the examples/ cells, libFuzzer
// mutates every part. A cell the builder rejects must throw with a message; a crash,
// sanitizer report or timeout is a finding. Invariant: every data register reads back
// within 16 bits after the run.
#include <fuzzer/FuzzedDataProvider.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <string>

#include "plc_cell/core/address.h"
#include "plc_cell/sim/soft_cell.h"
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

// The thin adapter over today's sim path (src/cli/sim_command.cpp), so the target can move
// to a single validation entry point later by changing this function only.
void run_cell(const std::string& yaml, const std::string& il, uint64_t span_us, uint64_t scan_us) {
  const std::string cfg = scratch() + "/cell.yaml", prog = scratch() + "/cell.il";
  write(cfg, yaml);
  write(prog, il);
  plc_cell::SoftCell cell(cfg, prog);
  plc_cell::Plc& plc = cell.plc();
  if (!plc.set_mode(plc_cell::RunMode::Run)) return;
  plc_cell::VirtualRun run(plc, scan_us);
  run.run_for(span_us);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
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
    run_cell(yaml, il, span_us, 1000);
  } catch (const std::exception& e) {
    if (std::string(e.what()).empty()) std::abort();  // a rejection must say why
  }
  return 0;
}
