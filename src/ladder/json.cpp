// The ladder JSON of docs/ladder.md: the fields the page draws from, nothing internal.
#include "plc_cell/ladder/json.h"

namespace plc_cell {
namespace ladder {

namespace {

nlohmann::json element_json(const Element& e) {
  nlohmann::json j{{"id", e.id}, {"row", e.row}, {"col", e.col}, {"type", e.type}, {"line", e.line},
                   {"instruction", e.instruction}};
  if (!e.form.empty()) j["form"] = e.form;
  if (!e.address.empty()) {
    j["address"] = e.address;
    j["name"] = e.name;
  }
  if (!e.comment.empty()) j["comment"] = e.comment;
  if (e.type == "timer" || e.type == "counter") {
    j["preset"] = e.preset;
    j["values"] = e.values;
    if (!e.preset_address.empty()) j["preset_address"] = e.preset_address;
  }
  if (e.type == "fun") {
    j["fun"] = e.fun;
    j["mnemonic"] = e.mnemonic;
    j["pulse"] = e.pulse;
    j["d32"] = e.d32;
    nlohmann::json inputs = nlohmann::json::array();
    for (const FunInput& in : e.inputs) inputs.push_back({{"name", in.name}, {"row", in.row}});
    j["inputs"] = inputs;
  }
  if (e.type == "fun" || !e.operands.empty()) {
    nlohmann::json ops = nlohmann::json::array();
    for (const FunOperand& o : e.operands) {
      nlohmann::json x{{"name", o.name}, {"text", o.text}};
      if (!o.address.empty()) x["address"] = o.address;
      if (!o.signal.empty()) x["signal"] = o.signal;
      ops.push_back(x);
    }
    j["operands"] = ops;
  }
  if (!e.label.empty()) j["label"] = e.label;
  return j;
}

nlohmann::json wire_json(const Wire& w) {
  if (w.vertical) return {{"id", w.id}, {"col", w.col}, {"from", w.from}, {"to", w.to}, {"v", true}};
  return {{"id", w.id}, {"row", w.row}, {"from", w.from}, {"to", w.to}};
}

}  // namespace

nlohmann::json to_json(const Network& n) {
  nlohmann::json il = nlohmann::json::array(), elements = nlohmann::json::array(),
                 wires = nlohmann::json::array();
  for (const IlLine& l : n.il) il.push_back({{"line", l.line}, {"text", l.text}});
  for (const Element& e : n.elements) elements.push_back(element_json(e));
  for (const Wire& w : n.wires) wires.push_back(wire_json(w));
  return {{"index", n.index}, {"line", n.line}, {"comment", n.comment}, {"drawable", n.drawable},
          {"reason", n.reason}, {"il", il}, {"rows", n.rows}, {"cols", n.cols},
          {"elements", elements}, {"wires", wires}, {"instructions", {n.first, n.end}}};
}

nlohmann::json to_json(const Layout& layout) {
  nlohmann::json nets = nlohmann::json::array();
  for (const Network& n : layout.networks) nets.push_back(to_json(n));
  nlohmann::json signals = nlohmann::json::object();
  for (const auto& s : layout.signals) {
    const std::string a = format_address(s.second);
    if (!signals.contains(a)) signals[a] = s.first;
  }
  return {{"file", layout.file}, {"version", layout.version}, {"networks", nets}, {"signals", signals}};
}

nlohmann::json to_json(const Flow& flow) { return {{"net", flow.net}, {"on", flow.on}}; }

}  // namespace ladder
}  // namespace plc_cell
