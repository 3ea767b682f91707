#pragma once
// A made-up subsystem, written as a new subsystem is (docs/architecture.md, "How to add an
// extension"): a `ticker: {start: N}` section, FUN 901 TICKS that counts its enabled scans,
// the probe ticker.count (its facet), its status, and registered for every cell built while a
// TickerRegistration lives. Its ROS side (a topic) is test/extension/ticker_ros.h.
#include <memory>
#include <string>

#include "plc_cell/config/extension_registry.h"
#include "plc_cell/config/probe_facet.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/scan_engine.h"
#include "plc_cell/scenario/probe.h"

namespace ticker {

using namespace plc_cell;

struct State {
  int64_t ticks = 0;
};

class Probes : public ProbeFacet {
 public:
  explicit Probes(State* s) : s_(s) {}
  std::vector<std::string> families() const override { return {"ticker"}; }
  std::string check(Plc&, const ProbeRef& p, bool writing) const override {
    if (writing) return p.text + ": the ticker is read, not driven";
    return p.name == "count" && p.field.empty() ? "" : p.text + ": the ticker has ticker.count only";
  }
  ProbeReading read(Plc& plc, const ProbeRef&) const override {
    ProbeReading r;
    r.number = double(plc.locked([&](ScanEngine&, Memory&) { return s_->ticks; }));
    r.text = probe_number_text(r.number);
    return r;
  }

 private:
  State* s_;
};

class Extension : public CellExtension {
 public:
  std::string name() const override { return "ticker"; }
  std::vector<std::string> sections() const override { return {"ticker"}; }
  void install(const CellConfig&, FunctionTable& t) override {
    FunctionSpec s;
    s.number = 901;
    s.mnemonic = "TICKS";
    s.handler = [](ExecContext& c, const BoundOperand*) {
      if (c.engine)
        if (State* st = c.engine->extensions().get<State>()) ++st->ticks;
    };
    t.add(s);
  }
  void attach(const CellConfig& cfg, Plc& plc, ErrorList& errors) override {
    const YAML::Node n = cfg.document.IsMap() ? cfg.document["ticker"] : YAML::Node();
    errors.collect([&] {
      if (n && n["start"]) state_.ticks = n["start"].as<int64_t>();
    }, cfg.file, n);
    plc.locked([&](ScanEngine& e, Memory&) {
      e.extensions().attach(&state_);
      return 0;
    });
    provide<State>(&state_);
    provide<ProbeFacet>(&probes_);
  }
  std::vector<ExtensionStatus> status(Plc& plc) const override {
    ExtensionStatus s;
    s.name = "ticker";
    s.message = std::to_string(plc.locked([&](ScanEngine&, Memory&) { return state_.ticks; })) + " ticks";
    return {s};
  }
  void detach(Plc& plc) override {
    withdraw<ProbeFacet>(&probes_);
    withdraw<State>(&state_);
    plc.locked([&](ScanEngine& e, Memory&) {
      e.extensions().detach(&state_);
      return 0;
    });
  }

 private:
  State state_;
  Probes probes_{&state_};
};

// The one registration line of the subsystem, and of its probe family.
struct Registration {
  ExtensionRegistration extension{"ticker", [] { return std::make_unique<Extension>(); }};
  scenario::ProbeFamilyRegistration family{"ticker"};
};

}  // namespace ticker
