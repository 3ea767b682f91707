#pragma once
// A subsystem of a cell (the counters, the axes, the temperature modules, FUN150/151 and
// their ports, the protocol servers' settings) as the cell is assembled. Every subsystem
// goes through the same steps, run by SoftCell in one place:
//   install  before the program is parsed: its FUN instructions (and what they need);
//   attach   once the PLC exists: read its sections of the cell YAML and attach to the
//            PLC (scan hooks; its typed slot in ScanEngine::extensions(), which its FUN
//            handlers reach in O(1));
//   status   what it reports (/diagnostics);
//   detach   off the PLC before the PLC goes, its threads stopped.
// What it shows to the outside it declares once, as facets: small interfaces looked up by
// type (get<ProbeFacet>(), get<hsc::HscUnit>()), so that the scenario targets, plc_node and
// the tool reach a subsystem without naming it. Its ROS topic groups are registered on the
// ROS side under its name (ros/extension_ros.h).
// A new subsystem is a class implementing this and one registration where the cell is
// assembled (docs/architecture.md, "Extensions").
#include <string>
#include <typeindex>
#include <typeinfo>
#include <utility>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/core/plc.h"

namespace plc_cell {

struct ExtensionStatus {
  enum class Level { Ok, Warn, Error };
  std::string name;  // "counters", "axis pso0"
  Level level = Level::Ok;
  std::string message;
  std::vector<std::pair<std::string, std::string>> values;
};

class CellExtension {
 public:
  virtual ~CellExtension() = default;
  virtual std::string name() const = 0;
  // The top-level keys of the cell YAML it reads ("counters"); an error of attach is
  // placed at the first of them when it has no line of its own.
  virtual std::vector<std::string> sections() const { return {}; }
  // Throws plc_cell::Error or SourceError; a failure leaves the instruction set incomplete,
  // so the program is not parsed (its FUN lines would only repeat the error).
  virtual void install(const CellConfig& cfg, FunctionTable& t) {
    (void)cfg;
    (void)t;
  }
  // Reads its sections into errors (going on after an error where it can, as an empty
  // subsystem) and attaches to plc.
  virtual void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) = 0;
  // The PLC lock is not held: take it for the memory copy and no more.
  virtual std::vector<ExtensionStatus> status(Plc& plc) const {
    (void)plc;
    return {};
  }
  // Off plc: hooks removed, threads and ports stopped. Called once, in reverse order.
  virtual void detach(Plc& plc) = 0;

  // The facet of type F it declared, or nullptr. Facets are declared in attach (the
  // objects they point to are made there) and stay until detach. Found by type_index,
  // which compares equal across the shared libraries of the layers.
  template <class F>
  F* get() const {
    for (const auto& f : facets_)
      if (f.first == std::type_index(typeid(F))) return static_cast<F*>(f.second);
    return nullptr;
  }

 protected:
  template <class F>
  void provide(F* facet) {
    withdraw<F>(get<F>());
    if (facet) facets_.emplace_back(std::type_index(typeid(F)), facet);
  }
  template <class F>
  void withdraw(const F* facet) {
    for (auto it = facets_.begin(); it != facets_.end(); ++it)
      if (it->first == std::type_index(typeid(F)) && it->second == facet) {
        facets_.erase(it);
        return;
      }
  }

 private:
  std::vector<std::pair<std::type_index, void*>> facets_;
};

}  // namespace plc_cell
