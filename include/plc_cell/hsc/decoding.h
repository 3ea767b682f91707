#pragma once
// The TRi FMD1616 quadrature decodings (TRi manual §7.1-7.3) as an option of an
// A/B counter: how one change of the A and B inputs moves CV when the counter's
// `decoding:` is set. Without it the counter counts by its FATEK mode (count_rule.h).
//
// "enhanced" is the one decoding with a memory: which phase changed last. It
// matters only while both phases are OFF, so an analytic source moving one way
// meets it at most at its first boundary; the counters step it through explicitly
// (docs/counters-and-interrupts.md "TRi encoder decoding").
#include <cstdint>
#include <string>

#include "plc_cell/hsc/count_rule.h"

namespace plc_cell {
namespace hsc {

enum class Decoding : uint8_t { Fatek = 0, Simple, Enhanced, X1, X2, X4 };

// "simple" -> Simple, ...; false for any other name (Fatek has no name: it is the default).
bool decoding_from_name(const std::string& name, Decoding* d);
const char* decoding_name(Decoding d);  // "" for Fatek

// The decoder's memory: the phase whose edge it saw last (0 = A, 1 = B), -1 when
// it cannot tell (RUN, or after a step that changed both phases).
struct DecodeState {
  int8_t last = -1;
};

// CV change for before -> after under decoding d of a counter in mode m, and the
// decoder's memory after it. Fatek counts by m (count_delta); the others are for
// A/B counters.
int decode_delta(Mode m, Decoding d, DecodeState* s, Pins before, Pins after);

}  // namespace hsc
}  // namespace plc_cell
