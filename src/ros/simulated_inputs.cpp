// ~simulate: inputs handed back from the topics to the cell's simulation. A publish on
// ~inputs/<name> takes an input from the simulation; this gives it back, so a test or an
// operator can play a sensor for a while and then let the cell's own signal run again.
#include <algorithm>

#include "plc_cell/core/address.h"
#include "plc_cell/ros/plc_node.h"

namespace plc_cell {

bool PlcNode::on_simulate(SimulateInputs::Request& req, SimulateInputs::Response& res) {
  res.success = false;
  std::vector<uint32_t> xs;
  for (const auto& name : req.inputs) {
    Address a;
    try {
      a = resolve(name);
    } catch (const std::exception& e) {
      res.message = "~simulate: " + std::string(e.what());
      return true;
    }
    if (a.area != Area::X || a.width != Width::Bit) {
      res.message = "~simulate: " + name + " is not an input (X)";
      return true;
    }
    xs.push_back(a.index);
  }
  const std::string refused = cell_->plc().locked([&](ScanEngine&, Memory&) -> std::string {
    SimulatedCell& sim = cell_->soft().simulation();
    if (req.inputs.empty()) xs = sim.simulated_inputs();
    for (size_t i = 0; i < xs.size(); ++i)
      if (!sim.simulates(xs[i]))
        return req.inputs[i] + ": the cell's simulation has no signal on X" + std::to_string(xs[i]);
    return "";
  });
  if (!refused.empty()) {
    res.message = "~simulate: " + refused + " (nothing handed back)";
    return true;
  }
  // From the next scan (the driver's), after the stamped inputs it has queued before.
  for (uint32_t x : xs) {
    TimedInput in;
    in.x = x;
    in.resume = true;
    input(in);
  }
  for (uint32_t x : xs) res.simulated.push_back("X" + std::to_string(x));
  res.success = true;
  res.message = std::to_string(xs.size()) + (xs.size() == 1 ? " input" : " inputs") + " simulated again";
  return true;
}

}  // namespace plc_cell
