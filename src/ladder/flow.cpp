// Power flow from two frames of values: each node from the ones before it (nodes are in
// evaluation order), then every element and wire from its node.
#include "plc_cell/ladder/flow.h"

#include <algorithm>

#include "elements.h"

namespace plc_cell {
namespace ladder {

namespace {

bool closed(const Element& e, const Lookup& now, const Lookup& prev) {
  const Address& a = e.bit;
  const bool v = now(a) != 0;
  if (e.form == "nc") return !v;
  if (e.form == "up") return v && prev(a) == 0;
  if (e.form == "down") return !v && prev(a) != 0;
  return v;
}

}  // namespace

Flow flow(const Network& network, const Lookup& now, const Lookup& prev) {
  Flow f;
  f.net = network.index;
  std::vector<const Element*> by_id;
  for (const Element& e : network.elements) {
    if (by_id.size() <= static_cast<size_t>(e.id)) by_id.resize(e.id + 1, nullptr);
    by_id[e.id] = &e;
  }
  std::vector<char> powered(network.nodes.size(), 0);
  for (size_t n = 0; n < network.nodes.size(); ++n) {
    const PowerNode& node = network.nodes[n];
    if (node.from.empty()) {
      powered[n] = 1;  // the left rail
    } else if (node.contact >= 0) {
      powered[n] = powered[node.from[0]] && closed(*by_id[node.contact], now, prev);
    } else {
      powered[n] = std::any_of(node.from.begin(), node.from.end(), [&](int k) { return powered[k] != 0; });
    }
  }
  auto on = [&](int node) { return node >= 0 && powered[node]; };
  for (const Element& e : network.elements)
    if (e.type == "contact" ? on(e.out) : on(e.in)) f.on.push_back(e.id);
  for (const Wire& w : network.wires)
    if (on(w.node)) f.on.push_back(w.id);
  std::sort(f.on.begin(), f.on.end());
  return f;
}

void Values::set(const Address& a, uint32_t v) { values_[address_key(a)] = v; }

uint32_t Values::get(const Address& a) const {
  auto it = values_.find(address_key(a));
  return it == values_.end() ? 0 : it->second;
}

}  // namespace ladder
}  // namespace plc_cell
