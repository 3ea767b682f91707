#pragma once
// What the monitor shows, wherever it comes from: the cell in this process (live), a real
// PLC over its host link (remote), or a recorded run (replay). The HTTP/WebSocket server
// (monitor/http_server.h) and the page know only this interface, so the three look the same
// to the user (docs/monitor.md).
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/config/cell_extension.h"
#include "plc_cell/core/address.h"
#include "plc_cell/core/plc.h"
#include "plc_cell/core/program.h"
#include "plc_cell/core/scan_stats.h"
#include "plc_cell/io/server.h"

namespace plc_cell {
namespace monitor {

// The program the ladder is drawn from: the IL text (comments included) and its parse.
struct ProgramView {
  std::string file;  // as shown to the user
  std::string text;  // the IL source
  Program program;
  std::vector<std::pair<std::string, Address>> signals;  // the cell's names, file order
  uint64_t version = 0;  // changes when the program is reloaded (online change)
};

// One consistent instant: every value read between the same two scans.
struct Frame {
  uint64_t scan = 0;  // scans since start
  uint64_t t_us = 0;  // the cell's clock: virtual time in sim and replay
  RunMode mode = RunMode::Stop;
  std::vector<uint32_t> values;  // one per address asked for, as Plc::read gives them
};

struct CellStatus {
  RunMode mode = RunMode::Stop;
  bool mode_switchable = false;  // RUN/STOP from the page is allowed
  ScanStats scan;
  std::vector<ExtensionStatus> extensions;  // each subsystem's panel
  std::vector<std::pair<std::string, ServerStatus>> servers;  // describe() -> status
  std::vector<Address> forced;  // disabled (forced) discretes
  std::string engine;           // "interpreter", "native", ... ("" when unknown)
  std::string note;             // e.g. "power flow computed from polled values"
};

// Recorded values over time (Replay::history): per address, its value at the first instant
// and then at each scan that changed it, as (t_us, value).
struct History {
  std::vector<std::vector<std::pair<uint64_t, uint32_t>>> series;
  std::optional<uint64_t> cut_us;  // too many changes: the series stop at this instant
};

// A recorded run's cursor (Source::replay()).
class Replay {
 public:
  virtual ~Replay() = default;
  virtual uint64_t begin_us() const = 0;
  virtual uint64_t end_us() const = 0;
  virtual uint64_t cursor_us() const = 0;
  virtual uint64_t scans() const = 0;
  // The failing check's instant and text of a failed scenario case, when the recording
  // has one.
  virtual std::optional<uint64_t> failure_us() const = 0;
  virtual std::string failure_text() const = 0;
  // Moves the cursor to the last scan at or before t_us (clamped to the run).
  virtual void seek(uint64_t t_us) = 0;
  // n scans (negative: back), or to the n-th next/previous event: a change of the
  // program's own addresses (what its ladder draws, the outputs, the named signals) or of
  // watched (the page's watch table); the clock relays and the real-time clock are none.
  virtual void step_scans(int64_t n) = 0;
  virtual void step_events(int64_t n, const std::vector<Address>& watched) = 0;
  // addrs from the last scan at or before from_us to the last at or before to_us.
  virtual History history(const std::vector<Address>& addrs, uint64_t from_us, uint64_t to_us) const = 0;
};

class Source {
 public:
  virtual ~Source() = default;
  virtual std::string describe() const = 0;  // "cell demo_conveyor", "FATEK 10.0.0.5:500"
  virtual std::shared_ptr<const ProgramView> program() const = 0;
  // Reads addrs at one instant. Throws plc_cell::Error saying why (link down, address
  // the PLC does not have). A live source holds the PLC lock for the copy only.
  virtual Frame read(const std::vector<Address>& addrs) = 0;
  // Edge memories are not readable from outside: the previous frame's values stand in
  // for them, and power flow through TU/TD contacts is computed from the two frames.
  virtual CellStatus status() = 0;
  // Writes, forcing and RUN/STOP; the server checks the writable ranges first. Throw
  // plc_cell::Error saying why (a recording refuses every one).
  virtual void write(const Address& start, const std::vector<uint32_t>& values) = 0;
  virtual void force(const Address& bit, ForceAction action) = 0;
  virtual void set_mode(RunMode mode) = 0;
  // Per instruction, Interpreter::kSeenOff | kSeenOn since the coverage was started;
  // nullopt when this source has no coverage.
  virtual std::optional<std::vector<uint8_t>> coverage() { return std::nullopt; }
  // The recorded run's cursor, or nullptr for a live or remote source.
  virtual Replay* replay() { return nullptr; }
  // The instruction set the program was parsed with (the ladder's FUN names and inputs);
  // nullptr: the core's.
  virtual const FunctionTable* functions() const { return nullptr; }
};

}  // namespace monitor
}  // namespace plc_cell
