// Trends: chosen registers or signals over a rolling window of the cell's time, drawn with
// dygraphs (Debian's libjs-dygraphs, served under /vendor/dygraphs/). Pause freezes the
// drawing (points keep being collected); CSV exports what the window holds.

import * as api from "./api.js";
import {show} from "./format.js";
import {addForm, download, html} from "./dom.js";

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
    this.build();
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

  // A frame: one point per series at the frame's instant (a replay may go back in time).
  addFrame(frame) {
    if (!this.series.length || frame.t_us === undefined) return;
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
        connectSeparatedPoints: true, animatedZooms: false, labelsSeparateLines: false});
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
