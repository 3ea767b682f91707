#pragma once
// A Plc in process as the LinkedPlc of a wall-clock target, with a link that can be made to
// fail: what the target and the restore do to a PLC, seen in its memory. Nothing scans it
// unless the test does.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "plc_cell/core/plc.h"
#include "plc_cell/io/transport.h"
#include "plc_cell/scenario/linked_plc.h"

namespace plc_cell {
namespace scenario_test {

class MemoryPlc : public scenario::LinkedPlc {
 public:
  Plc plc;
  bool can_force = true;
  bool knows_mode = true;
  int fail_next = 0;             // so many calls from now throw CommError (a lost link)
  std::string refuse_write_of;   // writes of this address are refused by the PLC (Error)
  std::vector<std::string> log;  // every call that changes the PLC: "write R0 5", "force X3 1", "unforce X3"
  uint64_t reads = 0;

  std::string describe() const override { return "the PLC in memory"; }
  std::string cannot_reach(const Address& a) const override {
    return a.area == Area::F ? format_address(a) + " is not on this PLC" : "";
  }
  std::vector<uint32_t> read(const std::vector<Address>& addrs) override {
    link();
    ++reads;
    std::vector<uint32_t> out;
    for (const auto& a : addrs) out.push_back(plc.read(a, 1).at(0));
    return out;
  }
  std::optional<std::vector<bool>> forced(const std::vector<Address>& bits) override {
    link();
    if (!can_force) return std::nullopt;
    std::vector<bool> out;
    plc.locked([&](ScanEngine&, Memory& m) {
      for (const auto& b : bits) out.push_back(m.disabled(b.area, b.index));
      return 0;
    });
    return out;
  }
  void write(const Address& a, uint32_t raw) override {
    link();
    if (format_address(a) == refuse_write_of) throw Error("PLC error A (illegal address) to " + format_address(a));
    plc.write(a, {raw});
    log.push_back("write " + format_address(a) + " " + std::to_string(raw));
  }
  void force(const Address& bit, bool on) override {
    link();
    if (!can_force) throw Error(cannot_force());
    plc.force(bit, ForceAction::Disable);
    plc.force(bit, on ? ForceAction::Set : ForceAction::Reset);
    log.push_back("force " + format_address(bit) + " " + (on ? "1" : "0"));
  }
  void unforce(const Address& bit) override {
    link();
    plc.force(bit, ForceAction::Enable);
    log.push_back("unforce " + format_address(bit));
  }
  std::string cannot_force() const override { return can_force ? "" : "this link has no force"; }
  std::optional<RunMode> mode() override {
    link();
    if (!knows_mode) return std::nullopt;
    return plc.mode();
  }
  std::string cannot_read_mode() const override { return knows_mode ? "" : "this link does not report RUN"; }

  bool disabled(const std::string& bit) const {
    const Address a = parse_address(bit);
    return plc.locked([&](const ScanEngine&, const Memory& m) { return m.disabled(a.area, a.index); });
  }
  uint32_t value(const std::string& addr) const { return plc.read(parse_address(addr), 1).at(0); }

 private:
  void link() {
    if (fail_next > 0) {
      --fail_next;
      throw CommError("the link is down");
    }
  }
};

}  // namespace scenario_test
}  // namespace plc_cell
