// The ladder's symbols, each drawn into a cell of the grid: x0..x0+w wide, its rung line at y.
// Every symbol is one <g> whose strokes turn thick and green when the element is energised
// (class "on", monitor.css). Labels: the address above the rung line, the signal name below.

import {svg} from "./dom.js";

export const CELL_W = 100;     // a contact column
export const OUTPUT_W = 230;   // the output column (coils, boxes)
export const RUNG_Y = 30;      // the rung line's offset from the row's top
export const ROW_H = 62;       // a row with no box
const STUB = 28;               // the wire into a box, room for an input's name
export const BOX_MARGIN = 10;  // what a box leaves free at the right of its column

const CONTACT_MARK = {no: "", nc: "/", up: "↑", down: "↓"};
const COIL_MARK = {out: "", out_not: "/", set: "S", rst: "R"};

function line(g, x1, y1, x2, y2, cls = "wire") {
  return svg("line", {x1, y1, x2, y2, class: cls}, g);
}

function labels(g, el, cx, y, onAddress) {
  if (el.address) {
    const a = svg("text", {x: cx, y: y - 16, class: "addr", "text-anchor": "middle"}, g, el.address);
    a.dataset.address = el.address;
    a.addEventListener("click", () => onAddress(el.address));
  }
  if (el.name) svg("text", {x: cx, y: y + 24, class: "name", "text-anchor": "middle"}, g, el.name);
}

export function contact(g, el, x0, w, y, onAddress) {
  const cx = x0 + w / 2;
  line(g, x0, y, cx - 8, y);
  line(g, cx + 8, y, x0 + w, y);
  line(g, cx - 8, y - 11, cx - 8, y + 11, "sym");
  line(g, cx + 8, y - 11, cx + 8, y + 11, "sym");
  const mark = CONTACT_MARK[el.form] || "";
  if (mark === "/") line(g, cx - 7, y + 10, cx + 7, y - 10, "sym");
  else if (mark) svg("text", {x: cx, y: y + 5, class: "mark", "text-anchor": "middle"}, g, mark);
  labels(g, el, cx, y, onAddress);
}

export function not(g, el, x0, w, y) {
  const cx = x0 + w / 2;
  line(g, x0, y, cx - 14, y);
  line(g, cx + 14, y, x0 + w, y);
  svg("rect", {x: cx - 14, y: y - 9, width: 28, height: 18, class: "sym box"}, g);
  svg("text", {x: cx, y: y + 4, class: "mark small", "text-anchor": "middle"}, g, "NOT");
}

export const COIL_X = 50;      // a coil's centre in the output column
export const COIL_W = 110;     // the output column when it holds coils only (name and tag included)

// The tag of a forced contact or coil ("F ON", "F OFF"), right of its symbol; empty until
// the point is forced.
export function forceTag(g, cx, y) {
  return svg("text", {x: cx + 11, y: y + 11, class: "forcetag"}, g, "");
}

export function coil(g, el, x0, w, y, onAddress) {
  const cx = x0 + COIL_X;
  line(g, x0, y, cx - 12, y);
  svg("path", {d: `M ${cx - 6} ${y - 12} A 14 14 0 0 0 ${cx - 6} ${y + 12}`, class: "sym"}, g);
  svg("path", {d: `M ${cx + 6} ${y - 12} A 14 14 0 0 1 ${cx + 6} ${y + 12}`, class: "sym"}, g);
  const mark = COIL_MARK[el.form] || "";
  if (mark) svg("text", {x: cx, y: y + 5, class: "mark", "text-anchor": "middle"}, g, mark);
  labels(g, el, cx, y, onAddress);
}

// A box at the output column: a title and lines of "label value" under it. Values that
// follow an address are <tspan data-value="ADDR">, filled in by every frame.
// A FUN's further inputs (el.inputs: [{name, row}], their rows' offsets in el.inputDy) come
// in from the left at their own rows, each with its name over the wire.
export function box(g, el, x0, w, y, title, rows, onAddress) {
  const inputs = el.inputs && el.inputs.length ? el.inputs : [{name: "", row: el.row}];
  const reach = Math.max(0, ...inputs.map((i) => (el.inputDy || {})[i.row] || 0));
  for (const input of inputs) {
    const iy = y + ((el.inputDy || {})[input.row] || 0);
    line(g, x0, iy, x0 + STUB, iy);
    if (input.name) svg("text", {x: x0 + 2, y: iy - 3, class: "input"}, g, input.name);
  }
  const h = Math.max(boxHeight(rows.length), reach + 26);
  svg("rect", {x: x0 + STUB, y: y - 14, width: w - STUB - BOX_MARGIN, height: h, rx: 3, class: "sym box"}, g);
  svg("text", {x: x0 + STUB + 8, y: y + 4, class: "boxtitle"}, g, title);
  rows.forEach((r, i) => {
    const t = svg("text", {x: x0 + STUB + 8, y: y + 22 + 16 * i, class: "boxrow"}, g);
    svg("tspan", {class: "oplabel"}, t, r.label ? `${r.label}: ` : "");
    const text = svg("tspan", {class: r.address ? "addr" : "operand"}, t, r.text);
    if (r.address) {
      text.dataset.address = r.address;
      text.addEventListener("click", () => onAddress(r.address));
      svg("tspan", {class: "value", "data-value": r.value || r.address}, t, "");
      if (r.signal) svg("tspan", {class: "name"}, t, ` ${r.signal}`);
    }
  });
}

export function boxHeight(nrows) {
  return 26 + 16 * nrows;
}

function timerRows(el) {
  const values = el.values || [];
  const current = values.find((v) => v !== el.address) || values[1];
  const rows = [{label: "PV", text: String(el.preset ?? ""), address: el.preset_address || null}];
  if (current) rows.push({label: "CV", text: current, address: current});
  if (el.address) rows.push({label: "out", text: el.address, address: el.address});
  return rows;
}

function funRows(el) {
  return (el.operands || []).map((op) => ({label: op.name, text: op.text ?? op.address ?? "",
                                           address: op.address || null, signal: op.signal || ""}));
}

// "FUN 8D MOV": the number with its 32-bit (D) and pulse (P) marks, then the mnemonic.
function funTitle(el) {
  const flags = `${el.d32 ? "D" : ""}${el.pulse ? "P" : ""}`;
  const name = el.mnemonic && !/^FUN\b/.test(el.mnemonic) ? ` ${el.mnemonic}` : "";
  return `FUN ${el.fun ?? ""}${flags}${name}`;
}

const FLOW_TITLE = {jump: "JMP", call: "CALL", label: "LBL"};

function otherTitle(el) {
  const head = FLOW_TITLE[el.type] || el.form || el.mnemonic || el.type.toUpperCase();
  return [head, el.label || ""].join(" ").trim();
}

// The rows an output box has (for the row's height before drawing).
export function outputRows(el) {
  if (el.type === "timer" || el.type === "counter") return timerRows(el);
  return funRows(el);
}

export function output(g, el, x0, w, y, onAddress) {
  switch (el.type) {
    case "coil":
      return coil(g, el, x0, w, y, onAddress);
    case "timer":
    case "counter":
      return box(g, el, x0, w, y, `${el.type === "timer" ? "TMR" : "CTR"} ${el.address || ""}`,
                 timerRows(el), onAddress);
    case "fun":
      return box(g, el, x0, w, y, funTitle(el), funRows(el), onAddress);
    default:
      return box(g, el, x0, w, y, otherTitle(el), funRows(el), onAddress);
  }
}

// An element that is not a contact inside the rung (a label, a flow mark): a small box.
export function inline(g, el, x0, w, y, onAddress) {
  box(g, el, x0, w, y, otherTitle(el), funRows(el), onAddress);
}
