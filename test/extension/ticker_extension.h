#pragma once
// A made-up subsystem, written as a new subsystem is (docs/architecture.md, "How to add an
// extension"): a `ticker: {start: N}` section, FUN 901 TICKS that adds its step (1 unless
// driven) at each enabled scan, the probes ticker.count (read) and ticker.step (driven by a
// scenario in its own stimuli, ticks or kticks), its status, and registered for every cell
// built while a Registration lives. Its ROS side (a topic) is test/extension/ticker_ros.h.
#include <memory>
#include <string>

#include "plc_cell/config/extension_registry.h"
#include "plc_cell/config/probe_facet.h"
#include "plc_cell/core/error.h"
#include "plc_cell/core/scan_engine.h"

namespace ticker {

using namespace plc_cell;

struct State {
  int64_t ticks = 0;
  int64_t step = 1;
};

class Probes : public ProbeFacet {
 public:
  explicit Probes(State* s) : s_(s) {}
  std::vector<std::string> families() const override { return {"ticker"}; }
  std::string check(Plc&, const ProbeRef& p, bool writing) const override {
    if (!p.field.empty() || (p.name != "count" && p.name != "step"))
      return p.text + ": the ticker has ticker.count and ticker.step only";
    if (writing != (p.name == "step")) return p.text + (writing ? ": it is read, not driven" : ": it is driven, not read");
    return "";
  }
  // v in ticks: "2 kticks" comes as 2000 "ticks" (the family's stimuli, below).
  void drive(Plc& plc, const ProbeRef&, const ProbeInput& v) const override {
    plc.locked([&](ScanEngine&, Memory&) { return s_->step = int64_t(v.value); });
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
        if (State* st = c.engine->extensions().get<State>()) st->ticks += st->step;
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

// The one registration line of the subsystem, and of its probe family with the stimuli its
// probes take (config/probe_facet.h).
struct Registration {
  ExtensionRegistration extension{"ticker", [] { return std::make_unique<Extension>(); }};
  ProbeFamilyRegistration family{ProbeFamily{"ticker", "a ticker", {{"ticks", {"ticks"}}, {"ticks", {"kticks"}, 1000}}, {}}};
};

}  // namespace ticker
