#pragma once
// FUN150 (Modbus master) and FUN151 (FATEK CPU link, free protocol) on the COM ports of
// the cell YAML's `ports:` section (and its older spellings in `fatek:` and `modbus:`,
// comm/port_config.h). A port both instructions use is one line with one owner
// (io/com_port.h). The Cell (runtime/cell.h) adds the extension to every cell; the
// simulation layers stay free of the protocol libraries.
#include <memory>
#include <vector>

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/cell_extension.h"
#include "plc_cell/core/function_table.h"
#include "plc_cell/io/com_ports.h"

namespace plc_cell {

// Throws SourceError listing every bad port entry (file:line:column and the key).
std::vector<std::shared_ptr<void>> install_protocol_functions(const CellConfig& cfg, FunctionTable& t);
// For `plc_cell check`: the same sections read with the same errors, and FUN150/151
// installed, but no port is opened and no thread started.
std::vector<std::shared_ptr<void>> check_protocol_functions(const CellConfig& cfg, FunctionTable& t);

// Both as a cell extension: open_ports false is `plc_cell check`'s (the sections read
// alike, the FUNs installed, no line opened and no thread started).
class ProtocolFunctions : public CellExtension {
 public:
  explicit ProtocolFunctions(bool open_ports = true) : open_ports_(open_ports) {}
  std::string name() const override { return "protocol functions"; }
  std::vector<std::string> sections() const override { return {"ports", "fatek", "modbus"}; }
  void install(const CellConfig& cfg, FunctionTable& t) override;
  void attach(const CellConfig&, Plc&, ErrorList&) override {}
  // One status per open COM port: its line, whether it is up (WARN with the last error
  // when not), the reopens and whether an instruction holds it.
  std::vector<ExtensionStatus> status(Plc& plc) const override;
  void detach(Plc&) override {  // the port threads stop before the PLC goes
    ports_.clear();
    com_ports_.reset();
  }

 private:
  bool open_ports_;
  std::vector<std::shared_ptr<void>> ports_;  // FUN151's and FUN150's sides, then the ports
  std::shared_ptr<ComPorts> com_ports_;
};

}  // namespace plc_cell
