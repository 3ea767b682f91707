#pragma once
// The cell in process as a scenario target: a fresh Cell (Purpose::Simulate) from the cell
// YAML and program, scanned in virtual time as `plc_cell sim` scans it.
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/runtime/cell.h"
#include "plc_cell/scenario/target.h"

namespace plc_cell {
namespace scenario {

class CellTarget : public Target {
 public:
  // Throws SourceError (the cell's or the program's errors) or Error. The PLC is put in RUN.
  // run: the front end's run settings (--engine).
  CellTarget(const std::string& cell_yaml, const std::string& program, const std::vector<SettingOverride>& run = {});
  // A cell someone else owns and scans (a cell of a line, line/line_target.h): read and
  // driven as the owned one is; its mode is left as it is.
  explicit CellTarget(Cell& borrowed) : cell_(&borrowed) {}
  ~CellTarget() override;

  Cell& cell() { return *cell_; }
  // Called after every scan with its instant (`plc_cell test --record` records there).
  void after_scan(std::function<void(uint64_t t_us)> hook) { after_scan_ = std::move(hook); }

  uint64_t period_us() const override;
  void scan(uint64_t t_us) override;
  std::string check(const Probe& p, bool writing) override;
  Reading read(const Probe& p) override;
  void set(const Probe& p, const Value& v) override;
  void write(const Probe& p, const Value& v) override;
  void force(const Probe& p, bool on) override;
  void release(const Probe* p) override;
  void simulate(const Probe* p) override;
  std::string fault() override;
  std::string label(const Probe& p) override { return probe_label(p, cell_->config()); }

 private:
  Plc& plc() { return cell_->plc(); }
  // The extension of cell that answers for p's family, or nullptr.
  static const ProbeFacet* facet(SoftCell& cell, const Probe& p);
  // Names resolve once: a condition is read at every scan.
  const Address& address(const std::string& name);
  std::unique_ptr<Cell> owned_;
  Cell* cell_ = nullptr;  // owned_, or the borrowed cell
  std::map<std::string, Address> addresses_;
  std::function<void(uint64_t)> after_scan_;
};

}  // namespace scenario
}  // namespace plc_cell
