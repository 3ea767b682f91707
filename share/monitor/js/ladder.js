// The ladder: every network of GET /api/ladder drawn as SVG from its grid (docs/ladder.md),
// energised elements and wires marked from each frame's flow, live values in the boxes,
// forced contacts and coils tagged with the state they are held in. A network that cannot
// be drawn shows its IL and the reason. Networks are numbered from 1, as coverage and
// mutation testing number them, with their IL line beside the number; the API's 0-based
// index is never shown.

import {html, svg} from "./dom.js";
import * as sym from "./symbols.js";

const LEFT = 14;  // the left power rail's x

// The y of each row's top, from the rows' heights (a row with a tall box is taller).
function rowTops(net) {
  const heights = new Array(Math.max(net.rows || 1, 1)).fill(sym.ROW_H);
  for (const el of net.elements || []) {
    const rows = sym.outputRows(el).length;
    if (rows && el.row < heights.length) heights[el.row] = Math.max(heights[el.row], sym.boxHeight(rows) + 18);
  }
  const tops = [0];
  for (const h of heights) tops.push(tops[tops.length - 1] + h);
  return tops;
}

function colX(c) {
  return LEFT + c * sym.CELL_W;
}

export class Ladder {
  constructor(container, onAddress) {
    this.container = container;
    this.onAddress = onAddress;
    this.nets = [];       // {net, div, parts: Map id -> [svg nodes], lines: Map line -> [nodes]}
    this.valueNodes = new Map();  // address -> [tspan]
    this.points = new Map();      // address -> [{g, tag}] of its contacts and coils
    this.signals = {};
  }

  render(data) {
    this.container.textContent = "";
    this.nets = [];
    this.valueNodes.clear();
    this.points.clear();
    this.note = html("p", {class: "flow-note", id: "flow-note", hidden: ""}, this.container);
    this.signals = data.signals || {};
    const networks = data.networks || [];
    if (!networks.length) html("p", {class: "empty"}, this.container, "The program has no networks.");
    for (const net of networks) this.nets.push(this.renderNetwork(net));
  }

  renderNetwork(net) {
    const div = html("section", {class: "net", id: `net-${net.index}`}, this.container);
    div.dataset.network = net.index;
    const head = html("header", {}, div);
    const line = net.line ? `line ${net.line}` : "";
    html("span", {class: "netno"}, head, net.number ? `network ${net.number}${line ? ` (${line})` : ""}` : line);
    html("span", {class: "comment"}, head, net.comment || "");
    const entry = {net, div, parts: new Map(), lines: new Map(), instructions: new Map(), on: new Set(),
                   text: this.searchText(net)};
    if (net.drawable === false) this.renderIl(entry);
    else this.renderSvg(entry);
    return entry;
  }

  searchText(net) {
    const words = [net.comment || ""];
    for (const el of net.elements || []) {
      words.push(el.address || "", el.name || this.signals[el.address] || "", el.mnemonic || "");
      for (const op of el.operands || []) words.push(op.text || "", op.address || "", this.signals[op.address] || "");
    }
    for (const l of net.il || []) words.push(l.text);
    return words.join(" ").toLowerCase();
  }

  renderIl(entry) {
    entry.div.classList.add("undrawable");
    html("p", {class: "reason"}, entry.div, `Not drawn as a ladder: ${entry.net.reason || "no reason given"}`);
    const pre = html("div", {class: "il"}, entry.div);
    for (const l of entry.net.il || []) {
      const row = html("div", {class: "illine"}, pre);
      html("span", {class: "lineno"}, row, String(l.line));
      html("span", {}, row, l.text);
      this.remember(entry.lines, l.line, row);
    }
  }

  renderSvg(entry) {
    const net = entry.net;
    const tops = rowTops(net);
    const cols = net.cols || 0;
    // As wide as the drawing and no wider: a network that fits its column gets no scrollbar.
    const boxes = (net.elements || []).some((el) => el.col >= cols && el.type !== "coil");
    const width = colX(cols) + (boxes ? sym.OUTPUT_W - sym.BOX_MARGIN + 2 : sym.COIL_W);
    const height = tops[tops.length - 1] + 4;
    const root = svg("svg", {class: "rung", width, height, viewBox: `0 0 ${width} ${height}`}, entry.div);
    svg("line", {x1: LEFT, y1: 2, x2: LEFT, y2: height - 2, class: "rail"}, root);
    const y = (row) => tops[Math.min(row, tops.length - 1)] + sym.RUNG_Y;
    for (const w of net.wires || []) {
      const node = w.v
        ? svg("line", {x1: colX(w.col), y1: y(w.from), x2: colX(w.col), y2: y(w.to), class: "wire"}, root)
        : svg("line", {x1: colX(w.from), y1: y(w.row), x2: colX(w.to), y2: y(w.row), class: "wire"}, root);
      this.remember(entry.parts, w.id, node);
    }
    for (const el of net.elements || []) this.renderElement(entry, root, el, cols, y(el.row), y);
    for (const node of root.querySelectorAll("[data-value]")) this.remember(this.valueNodes, node.dataset.value, node);
  }

  renderElement(entry, root, el, cols, y, rowY) {
    const g = svg("g", {class: `el ${el.type}`}, root);
    g.dataset.id = el.id;
    if (el.address) g.dataset.address = el.address;
    if (el.form) g.dataset.form = el.form;
    const named = {...el, name: el.name || this.signals[el.address] || "", inputDy: {}};
    for (const input of el.inputs || []) named.inputDy[input.row] = rowY(input.row) - y;
    const title = [el.address, named.name, el.comment, el.line ? `line ${el.line}` : ""].filter(Boolean).join("  ");
    if (title) svg("title", {}, g, title);
    if (el.col >= cols) sym.output(g, named, colX(cols), sym.OUTPUT_W, y, this.onAddress);
    else if (el.type === "contact") sym.contact(g, named, colX(el.col), sym.CELL_W, y, this.onAddress);
    else if (el.type === "not") sym.not(g, named, colX(el.col), sym.CELL_W, y);
    else sym.inline(g, named, colX(el.col), sym.CELL_W, y, this.onAddress);
    this.remember(entry.parts, el.id, g);
    if (el.address && (el.type === "contact" || el.type === "coil")) {
      const cx = el.col >= cols ? colX(cols) + sym.COIL_X : colX(el.col) + sym.CELL_W / 2;
      this.remember(this.points, el.address, {g, tag: sym.forceTag(g, cx, y)});
    }
    if (Number.isInteger(el.instruction)) this.remember(entry.instructions, el.instruction, g);
    else if (el.line) this.remember(entry.lines, el.line, g);
  }

  remember(map, key, node) {
    if (!map.has(key)) map.set(key, []);
    map.get(key).push(node);
  }

  entry(index) {
    return this.nets.find((e) => e.net.index === index);
  }

  // A frame's flow: [{net, on: [ids]}] for the networks it covers.
  applyFlow(flow) {
    for (const f of flow || []) {
      const e = this.entry(f.net);
      if (!e) continue;
      const on = new Set(f.on || []);
      for (const [id, nodes] of e.parts) {
        const now = on.has(id);
        if (now !== e.on.has(id)) for (const n of nodes) n.classList.toggle("on", now);
      }
      e.on = on;
    }
  }

  applyValues(values, format) {
    for (const [address, nodes] of this.valueNodes) {
      if (!(address in values)) continue;
      const text = ` = ${format(values[address])}`;
      for (const n of nodes) if (n.textContent !== text) n.textContent = text;
    }
  }

  // The frame's forced points (its keys among the networks' addresses): each contact and
  // coil of one tagged with the state it is held in.
  applyForced(forced, values) {
    const held = new Set(forced || []);
    for (const [address, marks] of this.points) {
      const on = held.has(address);
      const text = on ? `F ${Number(values[address]) ? "ON" : "OFF"}` : "";
      for (const {g, tag} of marks) {
        g.classList.toggle("forced", on);
        if (tag.textContent !== text) tag.textContent = text;
        g.dataset.forced = on ? (Number(values[address]) ? "on" : "off") : "";
      }
    }
  }

  // Why the frame draws no power flow (STOP, values not current), or null when it draws it.
  applyFlowNote(text, stale) {
    this.note.hidden = !text;
    this.note.textContent = text || "";
    this.container.classList.toggle("not-scanned", Boolean(text));
    this.container.classList.toggle("stale", Boolean(stale));
  }

  // Coverage: per instruction (elements) and per IL line (the listing of an undrawable
  // network), 0..3 (bit 0 evaluated with its rung off, bit 1 energised); null clears it.
  applyCoverage(cov) {
    const paint = (nodes, seen) => {
      for (const n of nodes) {
        n.classList.remove("cov-on", "cov-off", "cov-never");
        if (seen !== undefined) n.classList.add(seen & 2 ? "cov-on" : seen & 1 ? "cov-off" : "cov-never");
      }
    };
    for (const e of this.nets) {
      for (const [i, nodes] of e.instructions) paint(nodes, cov ? cov.seen[i] : undefined);
      for (const [line, nodes] of e.lines) paint(nodes, cov ? cov.byLine.get(line) : undefined);
    }
  }

  // Shows only the networks whose addresses, names, comment or IL contain the query.
  search(query) {
    const q = query.trim().toLowerCase();
    let shown = 0;
    for (const e of this.nets) {
      const hit = !q || e.text.includes(q);
      e.div.hidden = !hit;
      if (hit) shown++;
    }
    return shown;
  }
}
