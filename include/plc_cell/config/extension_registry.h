#pragma once
// Extensions a program adds to every cell it builds, beside the built-in ones (the
// counters, the axes, the modules) and the runtime's: a subsystem of another package, a
// made-up one in a test. A registration lasts as long as its object: cells built while it
// lives take the extension through every step, after the built-in ones, in the order
// registered.
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plc_cell/config/cell_extension.h"

namespace plc_cell {

using ExtensionFactory = std::function<std::unique_ptr<CellExtension>()>;

class ExtensionRegistration {
 public:
  ExtensionRegistration(std::string name, ExtensionFactory make);
  ~ExtensionRegistration();
  ExtensionRegistration(const ExtensionRegistration&) = delete;
  ExtensionRegistration& operator=(const ExtensionRegistration&) = delete;

 private:
  std::string name_;
};

// One of each registered extension, in the order registered.
std::vector<std::unique_ptr<CellExtension>> registered_extensions();

}  // namespace plc_cell
