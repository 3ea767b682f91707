#pragma once
// An extension's part of the whole-cell fuzz generator: what its YAML sections, IL and
// stimuli look like, written into a CellDraft. Each part registers itself from its own
// file (parts/*.cpp); a new extension adds its file and the generator runs it.
#include <string>
#include <vector>

#include "cell_draft.h"

namespace plc_cell_fuzz {

struct CellPart {
  std::string extension;  // the extension whose sections it writes ("axes", "counters")
  // Parts run in increasing order, so that the bytes drive the same choices whatever
  // the link order; a part that reserves pins for itself runs before those that take any.
  int order = 0;
  void (*generate)(CellDraft&) = nullptr;
};

// Every registered part, in order.
const std::vector<CellPart>& cell_parts();

struct RegisterCellPart {
  explicit RegisterCellPart(CellPart part);
};

}  // namespace plc_cell_fuzz
