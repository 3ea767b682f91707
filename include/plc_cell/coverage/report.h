#pragma once
// What a Recorder's totals mean, network by network, with the program's source lines:
// the one model the text, JSON and HTML outputs render (docs/coverage.md).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/address.h"
#include "plc_cell/core/program.h"

namespace plc_cell {
namespace coverage {

class Recorder;

// A cell's names of its points (signals: {stop_pb: X1}), in the cell YAML's order.
using SignalNames = std::vector<std::pair<std::string, Address>>;

enum class ItemKind : uint8_t {
  Contact,  // ORG/LD/AND/OR (NOT, TU, TD): the value of the device it reads
  Coil,     // OUT, OUT NOT, SET, RST, TMR, CTR: the rung result it receives
  Fun,      // FUN n, JMP, CALL: its EN input
};

struct Item {
  ItemKind kind = ItemKind::Contact;
  uint32_t index = 0;  // instruction index in the program
  int line = 0;
  std::string name;    // X4, OUT NOT Y1, TMR T50, FUN 8 MOV, CALL ADD_TEN
  std::string signal;  // the cell's name of the point it reads or drives (stop_pb), if any
  bool seen_off = false;
  bool seen_on = false;
  // A contact: some two scans differed in this contact alone, and in the network's
  // outcome (the results its coils and FUNs received): MC/DC, unique-cause form.
  bool mcdc = false;
  bool evaluated() const { return seen_off || seen_on; }
  // Contact changed, coil switched, FUN enabled: what the kind counts as exercised.
  bool exercised() const { return kind == ItemKind::Fun ? seen_on : seen_off && seen_on; }
};

struct Network {
  uint32_t number = 0;   // 1, 2, ... in program order, routines included
  int line = 0;          // its ORG
  int end_line = 0;      // its last instruction
  std::string routine;   // the LBL of the subroutine or interrupt routine; empty in the main program
  bool evaluated = false;  // its ORG ran
  bool energised = false;  // one of its coils or FUNs received a rung result ON
  std::vector<Item> items;
};

struct Totals {
  uint32_t networks = 0, networks_evaluated = 0, networks_energised = 0;
  uint32_t contacts = 0, contacts_changed = 0, contacts_mcdc = 0;
  uint32_t coils = 0, coils_switched = 0;
  uint32_t funs = 0, funs_enabled = 0;
};

// One thing a test did not exercise, in line order.
struct Finding {
  int line = 0;
  std::string message;  // "network 3 never energised", "contact X4 never changed (always OFF)"
};

struct Report {
  std::string file;    // the program file, as the Plc loaded it
  uint32_t runs = 0;   // recordings summed
  std::vector<Network> networks;
  Totals totals;
  std::vector<Finding> findings;
  // The program file's lines as report() read them (index 0 = line 1). If the file could
  // not be read, source_error says why and each instruction's line holds the instruction
  // as the parser saw it, so the HTML still shows the program.
  std::vector<std::string> source;
  std::string source_error;
};

// Throws plc_cell::Error if the recorder is empty.
Report report(const Recorder& r);

// The networks of p and their items, as report() divides them, with what seen says
// (seen: per instruction, Interpreter::kSeenOff | kSeenOn).
std::vector<Network> networks_of(const Program& p, const std::vector<uint8_t>& seen,
                                 const std::vector<std::string>& fun_names, const SignalNames& names);

// How the reports show an item: its name with the cell's signal name beside the address,
// "stop_pb (X1)", "OUT conveyor_run (Y0)"; the name alone when the point has none.
std::string label(const Item& it);

}  // namespace coverage
}  // namespace plc_cell
