// Cell status (GET /api/status and the WS status events): mode, scan statistics, faults,
// forced points, one panel per extension (drawn from its own entries, whatever it is: counters,
// axes, temperature, ...), the servers and their links.

import {html} from "./dom.js";

function us(ns) {
  return ns === undefined || ns === null ? "–" : `${(ns / 1000).toFixed(1)} µs`;
}

function keyValues(parent, pairs) {
  const table = html("table", {class: "kv"}, parent);
  for (const [k, v] of pairs) {
    const tr = html("tr", {}, table);
    html("th", {}, tr, String(k));
    html("td", {}, tr, v === undefined || v === null ? "–" : String(v));
  }
  return table;
}

function panel(parent, title, level = "ok", id = null) {
  const div = html("section", {class: `panel level-${level}`}, parent);
  if (id) div.id = id;
  const h = html("h3", {}, div, title);
  if (level !== "ok") html("span", {class: "badge"}, h, level);
  return div;
}

// Why RUN/STOP is not offered, or "" when it is: the server's reason (it knows the source
// and the writable ranges).
export function modeRefusal(status) {
  if (!status) return "the cell's status is not known yet";
  if (typeof status.mode_refusal === "string") return status.mode_refusal;
  return status.mode_switchable ? "" : "the server does not allow RUN/STOP from the page";
}

function forcedText(f) {
  const state = f.state === null || f.state === undefined ? "state not known" : `forced ${f.state ? "ON" : "OFF"}`;
  return `${f.address}${f.name ? ` ${f.name}` : ""}: ${state}`;
}

export function renderStatus(root, status) {
  root.textContent = "";
  const cell = panel(root, "Scan", status.mode === "fault" ? "error" : "ok", "status-scan");
  const mode = [["mode", (status.mode || "").toUpperCase()], ["engine", status.engine || "–"]];
  const scan = status.scan;
  if (scan) {
    keyValues(cell, [...mode, ["scans", scan.scans], ["cycle avg", us(scan.cycle_avg_ns)],
                     ["cycle max", us(scan.cycle_max_ns)], ["wake avg", us(scan.wake_avg_ns)],
                     ["wake max", us(scan.wake_max_ns)],
                     ...(scan.wake_p99_ns !== undefined ? [["wake p99", us(scan.wake_p99_ns)]] : []),
                     ["overruns", scan.overruns]]);
  } else {
    keyValues(cell, mode);
    html("p", {class: "scan-note"}, cell, `scan figures: ${status.scan_note || "not known"}`);
  }
  if (status.note) html("p", {class: "note"}, cell, status.note);
  const exts = status.extensions || [];
  const faults = exts.filter((e) => e.level === "error");
  const fp = panel(root, "Faults", faults.length || status.fault ? "error" : "ok", "status-faults");
  if (status.fault) html("p", {}, fp, status.fault);
  for (const f of faults) html("p", {}, fp, `${f.name}: ${f.message}`);
  if (!faults.length && !status.fault) html("p", {class: "muted"}, fp, "none");
  const forced = status.forced || [];
  const fo = panel(root, "Forced points", forced.length ? "warn" : "ok", "status-forced");
  if (!forced.length) html("p", {class: "muted"}, fo, "none");
  const list = html("ul", {class: "forced"}, fo);
  for (const f of forced) html("li", {"data-address": f.address}, list, forcedText(f));
  if (status.forced_note) html("p", {class: "note"}, fo, status.forced_note);
  for (const ext of exts) {
    const p = panel(root, ext.name, ext.level || "ok");
    p.classList.add("extension");
    p.dataset.extension = ext.name;
    if (ext.message) html("p", {}, p, ext.message);
    keyValues(p, ext.values || []);
  }
  renderServers(root, status.servers || []);
}

function renderServers(root, servers) {
  const p = panel(root, "Servers and links", servers.some((s) => s.link_up === false || !s.running) ? "warn" : "ok",
                  "status-servers");
  if (!servers.length) {
    html("p", {class: "muted"}, p, "none");
    return;
  }
  const table = html("table", {class: "grid"}, p);
  const head = html("tr", {}, table);
  for (const h of ["server", "state", "requests / rejected", "clients"]) html("th", {}, head, h);
  for (const s of servers) {
    const tr = html("tr", {}, table);
    const link = s.link_up === false ? ", link down" : "";
    const state = `${s.running ? "running" : "stopped"}${link}${s.last_error ? `: ${s.last_error}` : ""}`;
    for (const v of [s.name, state, `${s.requests ?? "–"} / ${s.rejected ?? "–"}`, s.connections ?? "–"])
      html("td", {}, tr, String(v));
  }
}
