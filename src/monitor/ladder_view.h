#pragma once
// The program as the monitor draws it: the ladder library's layout of every network, made
// once per program version, and the power flow of a network from two frames' values.
// The one place the server meets the ladder library (docs/ladder.md).
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "plc_cell/monitor/source.h"

namespace plc_cell {
namespace monitor {

class LadderView {
 public:
  LadderView(std::shared_ptr<const ProgramView> program, const FunctionTable* functions);
  ~LadderView();

  const ProgramView& program() const { return *program_; }
  size_t networks() const;
  nlohmann::json json() const;  // GET /api/ladder, each network with its "number"
  // What must be read to draw network n.
  std::vector<Address> addresses(size_t n) const;
  // The energised element and wire ids of network n; value(a) gives the frame's value of
  // an address of addresses(n), prev(a) the previous frame's.
  using Lookup = std::function<uint32_t(const Address&)>;
  std::vector<int> flow(size_t n, const Lookup& value, const Lookup& prev) const;

 private:
  struct Impl;
  std::shared_ptr<const ProgramView> program_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace monitor
}  // namespace plc_cell
