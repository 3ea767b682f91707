// The overview of a line's cells (docs/monitor.md, "One monitor for a line"): polls
// GET /api/overview and shows each cell's RUN/STOP, scan figures, faults and forced points,
// each wire's two ends, and the properties watched with the last one violated. When the
// server stops answering, a banner says so and every value on the page is marked stale
// with its age; a cell the server could not read is shown without a mode, with the reason.

import {html, keyedRows, setText} from "./dom.js";

const $ = (id) => document.getElementById(id);
const POLL_MS = 500;
const page = {last: null, lastAt: 0};

const us = (ns) => (ns === null || ns === undefined ? "–" : `${(ns / 1000).toFixed(1)} µs`);
const seconds = (t) => (t === null || t === undefined ? "–" : `${(t / 1e6).toFixed(3)} s`);
const span = (d) => (d < 1e6 ? `${d / 1000} ms` : seconds(d));

function modeText(mode) {
  return mode === "run" ? "RUN" : mode === "stop" ? "STOP" : "?";
}

function faultsText(c) {
  const out = [];
  if (c.stale) out.push(`not read: ${c.stale.error}`);
  if (c.note) out.push(c.note);
  for (const f of c.faults || []) out.push(`${f.name}: ${f.message || f.level}`);
  return out.join("; ");
}

function forcedText(c) {
  return (c.forced || []).map((f) => {
    const state = f.state === null || f.state === undefined ? "state not known" : f.state ? "ON" : "OFF";
    return `${f.address}${f.name ? " " + f.name : ""}: forced ${state}`;
  }).join(", ");
}

const CELL_COLUMNS = ["name", "mode", "scans", "cycle", "overruns", "clock", "faults", "forced"];

function renderCells(cells) {
  keyedRows($("cells").querySelector("tbody"), cells, (c) => c.name, (tr, c) => {
    tr.dataset.cell = c.name;
    for (const column of CELL_COLUMNS) html("td", {class: column}, tr);
    html("a", {class: "cell-link"}, tr.querySelector("td.name"), c.name);
  }, (tr, c) => {
    const td = (column) => tr.querySelector(`td.${column}`);
    const link = tr.querySelector("a.cell-link");
    if (link.getAttribute("href") !== c.page) link.setAttribute("href", c.page);
    link.title = `${c.source}: its ladder, watch tables and trends`;
    const scan = c.scan || null;
    td("mode").dataset.mode = c.mode;
    setText(td("mode"), modeText(c.mode));
    setText(td("scans"), scan ? String(scan.scans) : "–");
    td("cycle").title = c.scan_note || "";
    setText(td("cycle"), scan ? `${us(scan.cycle_avg_ns)} / ${us(scan.cycle_max_ns)}` : "–");
    setText(td("overruns"), scan ? String(scan.overruns) : "–");
    setText(td("clock"), seconds(c.t_us));
    setText(td("faults"), faultsText(c));
    setText(td("forced"), forcedText(c));
  });
}

const WIRE_COLUMNS = ["from", "from-value", "to", "to-value", "wire-text"];

function renderWires(wires) {
  const value = (v) => (v === null || v === undefined ? "–" : String(v));
  keyedRows($("wires").querySelector("tbody"), wires.map((w, i) => ({w, i})), ({i}) => String(i), (tr, {i}) => {
    tr.dataset.wire = String(i);
    for (const column of WIRE_COLUMNS) html("td", {class: column}, tr);
  }, (tr, {w}) => {
    const td = (column) => tr.querySelector(`td.${column}`);
    setText(td("from"), w.from);
    setText(td("from-value"), value(w.from_value));
    setText(td("to"), w.to);
    setText(td("to-value"), value(w.to_value));
    setText(td("wire-text"), w.error ? `${w.text} — not read: ${w.error}` : w.text);
  });
}

// "at 12.345 s, for 3 ms" (or "for 3 ms so far" while it goes on).
function violationText(v) {
  return `at ${seconds(v.begin_us)}, for ${span(v.duration_us)}${v.ongoing ? " so far" : ""}`;
}

const valuesText = (v) => v.values.map((x) => `${x.name} = ${x.value}`).join(", ");

const PROPERTY_COLUMNS = ["text", "state", "violations", "last", "values"];

function renderProperties(o) {
  const table = $("property-table");
  const last = $("last-violated");
  table.hidden = o.properties === null;
  last.hidden = !o.last_violated;
  $("properties").textContent = o.properties_t_us === null || o.properties_t_us === undefined
    ? o.properties_note : `${o.properties_note}; evaluated up to ${seconds(o.properties_t_us)}`;
  if (o.last_violated) {
    const v = o.last_violated;
    setText(last, `last violated: ${v.text} ${violationText(v)} — ${valuesText(v)} (${v.where})`);
  }
  if (o.properties === null) return;
  keyedRows(table.querySelector("tbody"), o.properties.map((p, i) => ({p, i})), ({i}) => String(i), (tr, {i}) => {
    tr.dataset.property = String(i);
    for (const column of PROPERTY_COLUMNS) html("td", {class: column}, tr);
  }, (tr, {p}) => {
    const td = (column) => tr.querySelector(`td.${column}`);
    td("text").title = p.within_us ? `${p.where}; a violation counts past ${span(p.within_us)}` : p.where;
    setText(td("text"), p.text);
    td("state").dataset.state = p.state;
    setText(td("state"), p.state === "violated" ? `violated since ${seconds(p.since_us)}` : p.state);
    setText(td("violations"), String(p.violations));
    setText(td("last"), p.last ? violationText(p.last) : "–");
    setText(td("values"), p.last ? valuesText(p.last) : "–");
  });
}

function render(o) {
  $("kind").textContent = o.kind;
  $("kind").dataset.kind = o.kind;
  $("source").textContent = o.title || "";
  document.title = `${o.title || "plc_cell"} — monitor`;
  renderCells(o.cells);
  renderWires(o.wires);
  renderProperties(o);
}

// The values shown are those of the last answer: past it, they are marked stale with their age.
function markStale(why) {
  const age = page.lastAt ? ((Date.now() - page.lastAt) / 1000).toFixed(1) : null;
  $("banner").hidden = false;
  $("banner").textContent = age === null
    ? `the monitor does not answer (${why}): nothing to show`
    : `the monitor does not answer (${why}): the values below are ${age} s old`;
  document.body.classList.add("stale");
}

async function poll() {
  try {
    const r = await fetch("/api/overview", {cache: "no-store"});
    const o = await r.json();
    if (!r.ok) throw new Error(o.error || `HTTP ${r.status}`);
    page.last = o;
    page.lastAt = Date.now();
    render(o);
    $("banner").hidden = true;
    document.body.classList.remove("stale");
  } catch (e) {
    markStale(e.message);
  }
  setTimeout(poll, POLL_MS);
}

poll();
