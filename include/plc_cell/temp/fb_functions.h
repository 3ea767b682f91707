#pragma once
// The FB-generation temperature instructions (second source, chapter 20): FUN72 TP4,
// FUN73 TSTC, FUN85 TPSNS and the FB version of FUN86 TPCTL. A cell gets them with
// modules.generation: FB; an FBs cell (the default) reports them as belonging to the
// FB generation. docs/analog-and-temperature.md, "FB generation".
namespace plc_cell {
class FunctionTable;
namespace temp {

// FUN72, FUN73, FUN85 and the FB FUN86 (t must not hold the FBs FUN86).
void add_fb_temperature_functions(FunctionTable& t);
// Notes for the parser: FUN72/73/85 belong to the FB generation.
void add_fb_only_notes(FunctionTable& t);

}  // namespace temp
}  // namespace plc_cell
