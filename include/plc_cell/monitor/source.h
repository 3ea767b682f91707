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
#include "plc_cell/config/program_changes.h"
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

// What a page shows: the cell in this process, a real PLC over its host link, a recording.
enum class SourceKind { Live, Remote, Replay };
const char* kind_text(SourceKind k);  // "live", "remote", "replay"

// What a page may ask a source to change (Source::refusal).
enum class Change { Write, Force, Mode };

// One consistent instant: every value read between the same two scans.
struct Frame {
  uint64_t scan = 0;  // scans since start
  uint64_t t_us = 0;  // the cell's clock: virtual time in sim and replay
  RunMode mode = RunMode::Stop;
  // false: the source cannot tell RUN from STOP (a TRi reports neither until this source
  // switched it); mode is then meaningless.
  bool mode_known = true;
  std::vector<uint32_t> values;  // one per address asked for, as Plc::read gives them
  // One per address: 1 when that discrete is forced (its DISABLE flag set). Empty when the
  // source cannot tell; a word address is never marked.
  std::vector<uint8_t> forced;
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
  bool mode_known = true;       // false: RUN or STOP cannot be told now (a link that is down)
  std::string scan_note;        // why `scan` holds no scan figures of the PLC ("" = it does)
  std::string forced_note;      // where `forced` comes from, or why it cannot be known
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
  virtual SourceKind kind() const = 0;
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
  // Why a page may never make this change here, whatever the writable ranges ("" = it
  // may): what the page greys out before a click rather than refuses after it.
  virtual std::string refusal(Change) const { return ""; }
  // The source's clock now (Frame::t_us's), without waiting on a link: the log's instants.
  virtual uint64_t now_us() { return read({}).t_us; }
  // Per instruction, Interpreter::kSeenOff | kSeenOn since the coverage was started;
  // nullopt when this source has no coverage.
  virtual std::optional<std::vector<uint8_t>> coverage() { return std::nullopt; }
  // The recorded run's cursor, or nullptr for a live or remote source.
  virtual Replay* replay() { return nullptr; }
  // The instruction set the program was parsed with (the ladder's FUN names and inputs);
  // nullptr: the core's.
  virtual const FunctionTable* functions() const { return nullptr; }
  // Changes of the running program (the Edit tab, docs/online-change.md); nullptr where the
  // program cannot be changed from here (a real PLC, a recording).
  virtual ProgramChanges* changes() { return nullptr; }
};

}  // namespace monitor
}  // namespace plc_cell
