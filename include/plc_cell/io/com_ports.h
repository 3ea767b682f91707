#pragma once
// The COM ports 1..4 a cell declares, each one ComPort shared by every instruction that
// uses it (FUN150 and FUN151 alike).
#include <map>
#include <memory>
#include <vector>

#include "plc_cell/io/com_port.h"

namespace plc_cell {

class ComPorts {
 public:
  ComPorts() = default;
  // A port for every line, each with its thread; the lines are tried now.
  explicit ComPorts(const std::map<int, ComLine>& lines) {
    for (const auto& l : lines) ports_[l.first] = std::make_shared<ComPort>(l.first, l.second);
  }
  void add(std::shared_ptr<ComPort> p) { ports_[p->number()] = std::move(p); }
  std::shared_ptr<ComPort> get(int n) const {
    const auto it = ports_.find(n);
    return it == ports_.end() ? nullptr : it->second;
  }
  bool empty() const { return ports_.empty(); }
  std::vector<int> numbers() const {
    std::vector<int> out;
    for (const auto& p : ports_) out.push_back(p.first);
    return out;
  }

 private:
  std::map<int, std::shared_ptr<ComPort>> ports_;
};

}  // namespace plc_cell
