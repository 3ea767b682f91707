// The overview of a line's cells (docs/monitor.md, "One monitor for a line"): polls
// GET /api/overview and shows each cell's RUN/STOP, scan figures, faults and forced points,
// and each wire's two ends. When the server stops answering, a banner says so and every
// value on the page is marked stale with its age; a cell the server could not read is shown
// without a mode, with the reason.

import {html} from "./dom.js";

const $ = (id) => document.getElementById(id);
const POLL_MS = 500;
const page = {last: null, lastAt: 0};

const us = (ns) => (ns === null || ns === undefined ? "–" : `${(ns / 1000).toFixed(1)} µs`);
const seconds = (t) => (t === null || t === undefined ? "–" : `${(t / 1e6).toFixed(3)} s`);

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

function renderCells(cells) {
  const body = $("cells").querySelector("tbody");
  body.textContent = "";
  for (const c of cells) {
    const tr = html("tr", {"data-cell": c.name}, body);
    const name = html("td", {}, tr);
    html("a", {href: c.page, class: "cell-link", title: `${c.source}: its ladder, watch tables and trends`}, name, c.name);
    html("td", {class: "mode", "data-mode": c.mode}, tr, modeText(c.mode));
    const scan = c.scan || null;
    html("td", {class: "scans"}, tr, scan ? String(scan.scans) : "–");
    html("td", {class: "cycle", title: c.scan_note || ""}, tr, scan ? `${us(scan.cycle_avg_ns)} / ${us(scan.cycle_max_ns)}` : "–");
    html("td", {class: "overruns"}, tr, scan ? String(scan.overruns) : "–");
    html("td", {class: "clock"}, tr, seconds(c.t_us));
    html("td", {class: "faults"}, tr, faultsText(c));
    html("td", {class: "forced"}, tr, forcedText(c));
  }
}

function renderWires(wires) {
  const body = $("wires").querySelector("tbody");
  body.textContent = "";
  wires.forEach((w, i) => {
    const tr = html("tr", {"data-wire": String(i)}, body);
    const value = (v) => (v === null || v === undefined ? "–" : String(v));
    html("td", {class: "from"}, tr, w.from);
    html("td", {class: "from-value"}, tr, value(w.from_value));
    html("td", {class: "to"}, tr, w.to);
    html("td", {class: "to-value"}, tr, value(w.to_value));
    html("td", {class: "wire-text"}, tr, w.error ? `${w.text} — not read: ${w.error}` : w.text);
  });
}

function render(o) {
  $("kind").textContent = o.kind;
  $("kind").dataset.kind = o.kind;
  $("source").textContent = o.title || "";
  document.title = `${o.title || "plc_cell"} — monitor`;
  renderCells(o.cells);
  renderWires(o.wires);
  $("properties").textContent = o.properties === null ? o.properties_note : "";
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
