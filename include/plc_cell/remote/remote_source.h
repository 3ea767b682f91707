#pragma once
// A real PLC as the monitor's source (monitor/source.h): the ladder is drawn from the
// user's IL copy of the program, the values come from the PLC through its host link (link.h)
// in coalesced polls of the addresses asked for, and power flow is computed from those
// values (CellStatus::note says so). Writes, forcing and RUN/STOP go through the protocol's
// own commands. A link that fails is reported down with its error; while it is down, a read
// within the retry interval fails at once rather than waiting on the line again. The PLC's
// forced points are read where its protocol can (FATEK 43), once a second, for the
// discretes the program names and the pages asked for. The PLC's scan figures are not
// known over a host link: none are given (the polls' own figures are the "polling" panel).
#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "plc_cell/core/function_table.h"
#include "plc_cell/monitor/source.h"
#include "plc_cell/remote/link.h"

namespace plc_cell {
namespace remote {

constexpr const char* kRemoteNote = "power flow computed from polled values";
constexpr const char* kRemoteScanNote = "not known: the PLC's host link does not report its scan figures";

// The user's IL copy as the monitor shows it. Throws SourceError (file:line:column) when it
// does not parse with functions.
std::shared_ptr<const monitor::ProgramView> load_program_view(
    const std::string& path, const FunctionTable& functions,
    std::vector<std::pair<std::string, Address>> signals = {});

class RemoteSource : public monitor::Source {
 public:
  // forced_every: how often the forced points of every discrete read so far are read again
  // (a discrete read for the first time has its own read at once).
  RemoteSource(std::unique_ptr<Link> link, std::shared_ptr<const monitor::ProgramView> program,
               std::chrono::milliseconds retry_after = std::chrono::milliseconds(1000),
               std::chrono::milliseconds forced_every = std::chrono::milliseconds(1000));

  monitor::SourceKind kind() const override { return monitor::SourceKind::Remote; }
  std::string describe() const override { return describe_; }
  std::shared_ptr<const monitor::ProgramView> program() const override { return program_; }
  monitor::Frame read(const std::vector<Address>& addrs) override;
  monitor::CellStatus status() override;
  void write(const Address& start, const std::vector<uint32_t>& values) override;
  void force(const Address& bit, ForceAction action) override;
  void set_mode(RunMode mode) override;
  std::string refusal(monitor::Change c) const override;
  uint64_t now_us() override;  // the monitor's time since it started: a PLC's clock is not read

  // Frames sent on the link so far.
  uint64_t frames() const;

 private:
  template <typename F>
  auto transact(const char* what, F&& f) -> decltype(f());
  // Under link_mu_: the forced points of the whole sweep list read again when forced_every
  // has passed, and of the discretes of addrs new to the list at once.
  void sweep_forced(const std::vector<Address>& addrs);
  static uint64_t key(const Address& a) { return uint64_t(a.area) << 32 | a.index; }
  std::string forced_note() const;  // under state_mu_

  std::unique_ptr<Link> link_;
  const std::string describe_;
  std::shared_ptr<const monitor::ProgramView> program_;
  const std::chrono::milliseconds retry_after_;
  const std::chrono::milliseconds forced_every_;
  const std::chrono::steady_clock::time_point created_ = std::chrono::steady_clock::now();
  std::mutex link_mu_;  // one transaction at a time on the line

  mutable std::mutex state_mu_;  // what status() reports, never held across a transaction
  bool link_up_ = false;
  bool tried_ = false;
  std::string last_error_;
  std::chrono::steady_clock::time_point failed_at_;
  RunMode mode_ = RunMode::Stop;
  bool mode_known_ = false;  // the link reported (or this source set) RUN or STOP
  uint64_t polls_ = 0, errors_ = 0, frames_ = 0;
  DurationStats poll_time_;
  // The discretes whose forced state is read (key -> address; under link_mu_), and which of
  // them are forced (under state_mu_).
  std::map<uint64_t, Address> sweep_;
  std::map<uint64_t, Address> forced_;
  bool forced_readable_ = true;
  std::string forced_error_;  // why the PLC would not tell
  bool swept_ = false;
  size_t swept_count_ = 0;
  std::chrono::steady_clock::time_point swept_at_;
};

}  // namespace remote
}  // namespace plc_cell
