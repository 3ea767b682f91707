#include "plc_cell/config/gate_config.h"

#include "plc_cell/config/cell_config.h"
#include "plc_cell/config/error_list.h"
#include "plc_cell/config/yaml_reader.h"

namespace plc_cell {

namespace {

std::string cell_file_folder(const std::string& file) {
  const auto slash = file.rfind('/');
  return slash == std::string::npos ? "" : file.substr(0, slash + 1);
}

// A duration ("20s", "500ms") within [lo_s, hi_s] seconds.
uint64_t bounded(const YamlReader& r, const YAML::Node& n, const std::string& key, uint64_t lo_s, uint64_t hi_s) {
  const uint64_t us = r.duration_us(n, key);
  if (us < lo_s * 1'000'000 || us > hi_s * 1'000'000)
    r.fail(n, key, "out of range [" + std::to_string(lo_s) + " s, " + std::to_string(hi_s) + " s]");
  return us;
}

class GateSection : public CellExtension {
 public:
  std::string name() const override { return "gate"; }
  std::vector<std::string> sections() const override { return {"gate"}; }
  void attach(const CellConfig& cfg, Plc&, ErrorList& errors) override {
    const YAML::Node at = cfg.document.IsMap() ? cfg.document["gate"] : YAML::Node();
    errors.collect([&] { gate_ = read_gate(cfg); }, cfg.file, at);
    provide<GateConfig>(&gate_);
  }
  void detach(Plc&) override {}

 private:
  GateConfig gate_;
};

}  // namespace

GateConfig read_gate(const CellConfig& cfg) {
  GateConfig g;
  const YAML::Node n = cfg.document.IsMap() ? cfg.document["gate"] : YAML::Node();
  if (!n || n.IsNull()) return g;
  YamlReader r(cfg.file);
  if (!n.IsMap()) r.fail(n, "gate", "expected a mapping: {scenarios: [...], explore: 20s, mutate: false}");
  r.only(n, "gate", {"scenarios", "explore", "mutate", "timeout"});
  g.line = YamlReader::line(n);
  const YAML::Node sc = n["scenarios"];
  if (!sc || !sc.IsSequence() || sc.size() == 0)
    r.fail(sc ? sc : n, "gate.scenarios", "expected a list of one or more scenario files");
  for (const auto& f : sc) {
    std::string path = r.str(f, "gate.scenarios");
    if (path.empty() || path[0] != '/') path = cell_file_folder(cfg.file) + path;
    g.scenarios.push_back(path);
  }
  if (n["explore"]) g.explore_us = bounded(r, n["explore"], "gate.explore", 0, 3600);
  if (n["mutate"]) g.mutate = r.boolean(n["mutate"], "gate.mutate");
  if (n["timeout"]) g.timeout_us = bounded(r, n["timeout"], "gate.timeout", 1, 600);
  return g;
}

std::unique_ptr<CellExtension> gate_section() { return std::make_unique<GateSection>(); }

}  // namespace plc_cell
