#pragma once
// The cell in this process as the monitor shows it (monitor/source.h). Every read holds the
// PLC lock for the copy of the values asked for only; status gathers the extensions'
// panels, the cell's servers and the scan statistics; coverage is recorded only from the
// first time a page asks for it.
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "plc_cell/config/server_kind.h"
#include "plc_cell/monitor/source.h"

namespace plc_cell {
namespace monitor {

class LiveSource : public Source {
 public:
  // context.config, extensions and servers may be absent (a bare Plc).
  explicit LiveSource(const ServerContext& context, std::string name = "cell");
  ~LiveSource() override;

  SourceKind kind() const override { return SourceKind::Live; }
  std::string describe() const override { return name_; }
  std::shared_ptr<const ProgramView> program() const override;
  Frame read(const std::vector<Address>& addrs) override;
  CellStatus status() override;
  void write(const Address& start, const std::vector<uint32_t>& values) override;
  void force(const Address& bit, ForceAction action) override;
  void set_mode(RunMode mode) override;
  std::optional<std::vector<uint8_t>> coverage() override;
  const FunctionTable* functions() const override { return &plc_.functions(); }
  ProgramChanges* changes() override { return changes_; }

 private:
  Plc& plc_;
  const CellConfig* config_;
  const std::vector<std::unique_ptr<CellExtension>>* extensions_;
  std::function<std::vector<const Server*>()> servers_;
  ProgramChanges* changes_;
  std::string name_;

  mutable std::mutex mu_;  // the program view and the coverage buffer (not the PLC)
  mutable std::shared_ptr<const ProgramView> view_;
  mutable std::vector<uint64_t> fingerprint_;
  std::unique_ptr<uint8_t[]> seen_;  // the interpreter records here once a page asked
  size_t seen_size_ = 0;
};

}  // namespace monitor
}  // namespace plc_cell
