#pragma once
// Builds a whole cell (YAML, IL program, simulation stimuli) from fuzzer bytes, from the
// grammar of the cell YAML and of the IL instructions the subsystems offer, so that most
// inputs are cells the builder accepts and the fuzzer's time goes into running them.
// Each extension writes its own part (parts/*.cpp, registered through cell_part.h); this
// runs them in order and assembles the cell.
// Every enum key is drawn from all of its documented values; FUN141's P15 fields are
// each "not configured" (FFH) some of the time; a small share of choices ignores the
// pin bookkeeping on purpose, so rejections are exercised too.
//
// Some axes are generated "wired": output UD, pins looped back to the HHSC of the same
// number in MD0, no backlash or compensation, moves that nothing cuts (no ACT, EXT,
// PAU or ABT). For those the generator records what the manual promises, and the fuzz
// target checks it (cell_invariants.h).
#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <string>
#include <vector>

namespace plc_cell_fuzz {

struct WiredAxis {
  int ps = 0;       // PSO0-PSO3; its pins feed HSC<ps> (MD0, U = X(4ps), D = X(4ps+1))
  bool homes = false;  // the table has a DRVZ step: DR4088 jumps to P16 at home
  // Per step (1-based, index 0 unused): the signed pulses a completed DRV step moves,
  // or no check (DRVZ).
  std::vector<int64_t> stroke;
  std::vector<bool> checked;
  std::vector<bool> absolute;  // an ABS step: the check is "position = stroke"
};

struct GeneratedCell {
  std::string yaml;
  std::string il;
  uint64_t scan_us = 1000;
  uint64_t span_us = 100000;
  std::vector<WiredAxis> wired;
};

GeneratedCell generate_cell(FuzzedDataProvider& fdp);

}  // namespace plc_cell_fuzz
