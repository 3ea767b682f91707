// Trends: chosen registers or signals over a rolling window of the cell's time, drawn with
// dygraphs (Debian's libjs-dygraphs, served under /vendor/dygraphs/). Live, the points are
// the frames as they come; in a replay, the window up to the cursor is the recorded
// history (GET /api/replay/history: every change, drawn as steps), not the instants the
// page happened to visit. Pause freezes the drawing (points keep being collected); CSV
// exports what the window holds. The time axis's labels carry as many decimals as their
// spacing needs, so no two read alike.

import * as api from "./api.js";
import {show} from "./format.js";
import {addForm, download, html} from "./dom.js";

// Ticks every 1, 2 or 5 times a power of ten, at least pixelsPerLabel apart, each labelled
// with the decimals its spacing needs (0.005 s apart: "1.475", "1.480"): no label repeats.
export function timeTicks(a, b, pixels, opts) {
  const perLabel = Number(opts("pixelsPerLabel")) || 60;
  const wanted = Math.max(1, Math.floor(pixels / perLabel));
  const raw = Math.max(Math.abs(b - a) / wanted, 1e-9);
  const power = Math.pow(10, Math.floor(Math.log10(raw)));
  const step = [1, 2, 5, 10].map((m) => m * power).find((v) => v >= raw * (1 - 1e-9));
  const decimals = Math.max(0, -Math.floor(Math.log10(step) + 1e-9));
  const ticks = [];
  for (let k = Math.ceil(Math.min(a, b) / step - 1e-9); k * step <= Math.max(a, b) + step * 1e-9; k++)
    ticks.push({v: k * step, label: (k * step).toFixed(decimals)});
  return ticks;
}

export class Trends {
  constructor(root, {changed, log}) {
    this.root = root;
    this.changed = changed;
    this.log = log;
    this.series = [];  // addresses or names
    this.rows = [];    // [t_s, v...], sorted by t
    this.windowS = 60;
    this.paused = false;
    this.graph = null;
    this.replay = null;  // a promise of whether the source is a recording
    this.shown = "";     // in a replay: the history drawn (series, window, cursor)
    this.build();
  }

  isReplay() {
    if (!this.replay) this.replay = api.session().then((s) => s.kind === "replay", () => false);
    return this.replay;
  }

  build() {
    addForm(this.root, "trend", "temp_pv, DR4088, RC0 ...", (a) => this.add(a));
    const bar = html("div", {class: "bar"}, this.root);
    html("label", {}, bar, "window (s) ");
    const win = html("input", {type: "number", min: 1, max: 3600, value: this.windowS, id: "trend-window"}, bar);
    win.addEventListener("change", () => (this.windowS = Math.max(1, Number(win.value) || 60)));
    this.pauseButton = html("button", {id: "trend-pause", onclick: () => this.togglePause()}, bar, "Pause");
    html("button", {id: "trend-clear", onclick: () => this.clear()}, bar, "Clear");
    html("button", {id: "trend-csv", onclick: () => this.exportCsv()}, bar, "Export CSV");
    this.points = html("span", {id: "trend-points", class: "muted"}, bar, "0 points");
    this.chips = html("div", {class: "chips"}, this.root);
    this.plot = html("div", {id: "trend-plot", class: "plot"}, this.root);
  }

  async add(address) {
    if (this.series.includes(address)) return;
    const why = await api.unreadable([address]);
    if (why) {
      this.log(`trend ${address}: ${why}`, "error");
      return;
    }
    this.series.push(address);
    this.rows = this.rows.map((r) => [...r, null]);
    this.redrawChips();
    this.resetGraph();
    this.changed();
  }

  remove(address) {
    const i = this.series.indexOf(address);
    if (i < 0) return;
    this.series.splice(i, 1);
    this.rows = this.rows.map((r) => r.filter((_, k) => k !== i + 1));
    this.redrawChips();
    this.resetGraph();
    this.changed();
  }

  redrawChips() {
    this.chips.textContent = "";
    for (const s of this.series) {
      const chip = html("span", {class: "chip"}, this.chips, s + " ");
      html("button", {title: `remove ${s}`, onclick: () => this.remove(s)}, chip, "×");
    }
  }

  addresses() {
    return this.series;
  }

  togglePause() {
    this.paused = !this.paused;
    this.pauseButton.textContent = this.paused ? "Resume" : "Pause";
    this.pauseButton.classList.toggle("active", this.paused);
    if (!this.paused) this.draw();
  }

  clear() {
    this.rows = [];
    this.draw();
  }

  // A frame: one point per series at the frame's instant; in a replay, the recorded
  // history up to the frame's instant.
  async addFrame(frame) {
    if (!this.series.length || frame.t_us === undefined) return;
    if (await this.isReplay()) return this.loadHistory(frame.t_us);
    const t = frame.t_us / 1e6;
    const row = [t, ...this.series.map((s) => (s in frame.values ? Number(show(frame.values[s], "signed")) : null))];
    let i = this.rows.length;
    while (i > 0 && this.rows[i - 1][0] > t) i--;
    if (i > 0 && this.rows[i - 1][0] === t) this.rows[i - 1] = row;
    else this.rows.splice(i, 0, row);
    const newest = this.rows[this.rows.length - 1][0];
    while (this.rows.length && this.rows[0][0] < newest - this.windowS) this.rows.shift();
    this.points.textContent = `${this.rows.length} points`;
    this.points.dataset.count = this.rows.length;
    if (!this.paused) this.draw();
  }

  async loadHistory(cursorUs) {
    const series = [...this.series];
    const fromUs = Math.max(0, cursorUs - Math.round(this.windowS * 1e6));
    const key = `${series.join(",")}|${fromUs}|${cursorUs}`;
    if (key === this.shown || key === this.loading) return;
    this.loading = key;
    let h;
    try {
      h = await api.get(`/api/replay/history?a=${encodeURIComponent(series.join(","))}&from_us=${fromUs}&to_us=${cursorUs}`);
    } catch (e) {
      this.shown = key;  // said once: not asked again until the cursor or the series change
      this.log(`trend: ${e.message}`, "error");
      return;
    } finally {
      if (this.loading === key) this.loading = null;
    }
    if (series.join(",") !== this.series.join(",")) return;  // changed while asking
    // One row at every instant a series changed, each series holding its last value.
    const points = series.map((s) => h.series[s] || []);
    const times = [...new Set(points.flat().map(([t]) => t))].sort((x, y) => x - y);
    const at = points.map(() => 0), value = points.map(() => null);
    const rows = [];
    for (const t of times) {
      points.forEach((p, i) => {
        while (at[i] < p.length && p[at[i]][0] <= t) value[i] = Number(show(p[at[i]++][1], "signed"));
      });
      rows.push([t / 1e6, ...value]);
    }
    const end = h.cut_us ?? cursorUs;
    if (rows.length && rows[rows.length - 1][0] < end / 1e6) rows.push([end / 1e6, ...value]);
    this.rows = rows;
    this.shown = key;
    const changes = points.reduce((n, p) => n + Math.max(0, p.length - 1), 0);
    this.points.textContent = `${changes} recorded changes` +
        (h.cut_us !== null && h.cut_us !== undefined ? ` (cut at ${(h.cut_us / 1e6).toFixed(3)} s: too many)` : "");
    this.points.dataset.count = rows.length;
    this.points.dataset.history = "recorded";
    if (!this.paused) this.draw();
  }

  resetGraph() {
    if (this.graph) this.graph.destroy();
    this.graph = null;
    this.plot.textContent = "";
    this.draw();
  }

  draw() {
    if (!this.series.length || !this.rows.length || this.plot.offsetParent === null) return;
    if (typeof window.Dygraph !== "function") {
      this.plot.textContent = "dygraphs is not available (/vendor/dygraphs/dygraph.min.js did not load)";
      return;
    }
    if (!this.graph) {
      this.graph = new window.Dygraph(this.plot, this.rows, {
        labels: ["t (s)", ...this.series], legend: "always", xlabel: "cell time (s)",
        connectSeparatedPoints: true, animatedZooms: false, labelsSeparateLines: false,
        stepPlot: this.points.dataset.history === "recorded",  // a recorded value holds until it changes
        axes: {x: {ticker: timeTicks}}});
    } else {
      this.graph.updateOptions({file: this.rows});
    }
  }

  exportCsv() {
    const lines = [["t_s", ...this.series].join(",")];
    for (const r of this.rows) lines.push(r.map((v) => (v === null ? "" : v)).join(","));
    download("trend.csv", lines.join("\n") + "\n", "text/csv");
  }
}
