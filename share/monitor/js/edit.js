// The Edit tab (docs/online-change.md): the running program's IL in an editor with IL
// highlighting (CodeMirror from Debian's libjs-codemirror, a plain text area without it),
// each parse error at its line, the networks that changed drawn old beside new, Test (the
// cell's gate, its report shown), Apply (only once the gate passed on this very text and the
// server allows changes), Apply anyway (gate failed: needs a reason), Undo, and the change
// log. Test, Apply and Undo are jobs on the server: the tab polls each until it is done.

import * as api from "./api.js";
import {html} from "./dom.js";
import {Ladder} from "./ladder.js";

const JOB_POLL_MS = 100;
const JOB_LIMIT_MS = 660000;  // the longest gate.timeout (600 s) and the swap after it
const CHECK_DELAY_MS = 250;

// FATEK IL for CodeMirror's simple mode: instructions, devices, operand names, comments.
function defineIlMode(CM) {
  if (!CM || !CM.defineSimpleMode || CM.modes["fatek-il"]) return;
  CM.defineSimpleMode("fatek-il", {
    start: [
      {regex: /;.*/, token: "comment"},
      {regex: /\b(?:ORG|LD|AND|OR|ANDLD|ORLD|OUT|SET|RST|TMR|CTR|FUN|END|LBL|JMP|CALL|RTS|RTI|FOR|NEXT|NOT|TU|TD)\b/i,
       token: "keyword"},
      {regex: /\b[A-Za-z]+=/, token: "attribute"},
      {regex: /\b(?:WX|WY|WM|WS|DWX|DWY|DWM|DWS|DR|DD|RT|RC|DRC|TR|CV|X|Y|M|S|T|C|R|D|V|Z)\d+\b/i, token: "variable-2"},
      {regex: /\b(?:K-?\d+|H[0-9A-F]+|-?\d+)\b/i, token: "number"},
      {regex: /\.(?:D|P)\b/i, token: "meta"},
    ],
  });
}

export class EditTab {
  constructor(panel, {log, tabShown}) {
    this.panel = panel;
    this.log = log;
    this.tabShown = tabShown;
    this.state = null;
    this.tested = null;     // {text, result} of the last gate that ran from this page
    this.checked = null;    // {text, result} of the last check
    this.checkTimer = null;
    this.build();
  }

  build() {
    const p = this.panel;
    this.head = html("p", {class: "edit-head muted", id: "edit-head"}, p, "");
    this.unavailable = html("p", {class: "edit-unavailable", id: "edit-unavailable", hidden: ""}, p);
    const tools = html("div", {class: "edit-tools"}, p);
    this.testButton = html("button", {id: "edit-test", title: "run the cell's gate on this program"}, tools, "Test");
    this.applyButton = html("button", {id: "edit-apply", disabled: ""}, tools, "Apply");
    this.undoButton = html("button", {id: "edit-undo", disabled: ""}, tools, "Undo");
    this.revertButton = html("button", {id: "edit-revert", title: "the running program's text again"}, tools, "Revert");
    this.status = html("span", {class: "edit-status", id: "edit-status"}, tools, "");
    this.forceBox = html("div", {class: "edit-force", id: "edit-force", hidden: ""}, p);
    html("span", {}, this.forceBox, "The gate failed. Apply anyway, because: ");
    this.reason = html("input", {id: "edit-reason", size: 30, placeholder: "the reason, kept in the change log"},
                       this.forceBox);
    this.forceButton = html("button", {id: "edit-force-apply", disabled: ""}, this.forceBox, "Apply anyway");
    const host = html("div", {class: "edit-editor", id: "edit-editor"}, p);
    this.area = html("textarea", {id: "edit-text", spellcheck: "false", rows: 18}, host);
    this.cm = null;
    if (window.CodeMirror) {
      defineIlMode(window.CodeMirror);
      this.cm = window.CodeMirror.fromTextArea(this.area, {lineNumbers: true, mode: "fatek-il",
                                                           gutters: ["CodeMirror-linenumbers", "il-errors"]});
      this.cm.on("change", () => this.changed());
    } else {
      html("p", {class: "muted"}, host, "IL highlighting needs Debian's libjs-codemirror (/vendor/codemirror).");
      this.area.addEventListener("input", () => this.changed());
    }
    this.errors = html("ul", {class: "edit-errors", id: "edit-errors"}, p);
    this.report = html("div", {class: "edit-report", id: "edit-report"}, p);
    html("h3", {}, p, "Networks changed (running | new)");
    this.diff = html("div", {class: "edit-diff", id: "edit-diff"}, p);
    html("h3", {}, p, "Change log");
    this.history = html("div", {class: "edit-log", id: "edit-log"}, p);
    this.testButton.addEventListener("click", () => this.runJob("test"));
    this.applyButton.addEventListener("click", () => this.runJob("apply"));
    this.forceButton.addEventListener("click", () => this.runJob("apply", true));
    this.undoButton.addEventListener("click", () => this.runJob("undo"));
    this.revertButton.addEventListener("click", () => this.setText(this.state ? this.state.text : ""));
    this.reason.addEventListener("input", () => this.buttons());
  }

  text() {
    return this.cm ? this.cm.getValue() : this.area.value;
  }

  setText(text) {
    if (this.cm) this.cm.setValue(text);
    else this.area.value = text;
    this.changed();
  }

  // The running program and what this server allows; the editor keeps what is typed in it.
  async load(keepText = false) {
    this.state = await api.get("/api/edit");
    if (!this.state.available) {
      this.unavailable.hidden = false;
      this.unavailable.textContent = this.state.why;
      for (const b of [this.testButton, this.applyButton, this.undoButton, this.revertButton]) b.disabled = true;
      return;
    }
    this.head.textContent = `${this.state.file} — running program ${this.state.hash}` +
      (this.state.gate ? "" : " — the cell names no gate (gate: in its YAML): Test has nothing to run");
    if (!keepText) this.setText(this.state.text);
    if (this.cm) this.cm.refresh();
    this.buttons();
    await this.loadLog();
  }

  changed() {
    clearTimeout(this.checkTimer);
    this.checkTimer = setTimeout(() => this.check(), CHECK_DELAY_MS);
    this.buttons();
  }

  async check() {
    const text = this.text();
    try {
      const result = await api.post("/api/edit/check", {text});
      if (text !== this.text()) return;  // typed on since: the next check shows it
      this.checked = {text, result};
      this.showErrors(result);
      this.showDiff(result);
    } catch (e) {
      this.status.textContent = `check: ${e.message}`;
    }
    this.buttons();
  }

  showErrors(result) {
    this.errors.textContent = "";
    if (this.cm) {
      this.cm.clearGutter("il-errors");
      for (let i = 0; i < this.cm.lineCount(); i++) this.cm.removeLineClass(i, "background", "il-error-line");
    }
    for (const e of result.errors || []) {
      const li = html("li", {class: "error"}, this.errors, `line ${e.line}${e.column ? `:${e.column}` : ""}: ${e.message}`);
      li.dataset.line = e.line;
      if (this.cm && e.line > 0) {
        this.cm.addLineClass(e.line - 1, "background", "il-error-line");
        const mark = html("span", {class: "il-error-mark", title: e.message}, null, "●");
        this.cm.setGutterMarker(e.line - 1, "il-errors", mark);
      }
    }
    for (const r of result.refusals || []) html("li", {class: "error refusal"}, this.errors, `not in RUN: ${r}`);
  }

  showDiff(result) {
    this.diff.textContent = "";
    const pairs = result.networks || [];
    if (!(result.errors || []).length && !pairs.length)
      html("p", {class: "muted"}, this.diff, "No network changed.");
    for (const pair of pairs) {
      const row = html("div", {class: "diff-row"}, this.diff);
      for (const side of ["old", "new"]) {
        const cell = html("div", {class: `diff-${side}`}, row);
        if (!pair[side]) {
          html("p", {class: "muted"}, cell, side === "old" ? "(added)" : "(removed)");
          continue;
        }
        new Ladder(cell, () => {}).render({networks: [pair[side]], signals: result.signals || {}});
      }
    }
  }

  gatePassedFor(text) {
    if (this.state && !this.state.gate) return true;
    return Boolean(this.tested && this.tested.text === text && this.tested.result.passed);
  }

  buttons() {
    const s = this.state;
    if (!s || !s.available) return;
    const text = this.text();
    const clean = this.checked && this.checked.text === text && !(this.checked.result.errors || []).length &&
      !(this.checked.result.refusals || []).length;
    const changed = text !== s.text;
    const busy = Boolean(this.busy);
    this.testButton.disabled = busy || !s.gate || !clean;
    const failed = this.tested && this.tested.text === text && !this.tested.result.passed;
    let why = "";
    if (!s.apply) why = s.apply_refusal;
    else if (!changed) why = "this is the running program";
    else if (!clean) why = "the program has errors, or does what a change in RUN may not";
    else if (!this.gatePassedFor(text)) why = failed ? "the gate failed on this program" : "run Test first: the gate must pass";
    this.applyButton.disabled = busy || why !== "";
    this.applyButton.title = why || "apply this program now, at a scan boundary";
    this.undoButton.disabled = busy || !s.apply;
    this.undoButton.title = s.apply ? "go back to the program the last change replaced" : s.apply_refusal;
    this.forceBox.hidden = !(failed && s.apply && clean && changed);
    this.forceButton.disabled = busy || !this.reason.value.trim();
  }

  async runJob(what, force = false) {
    const text = this.text();
    const body = what === "undo" ? {} : {text};
    if (force) Object.assign(body, {force: true, reason: this.reason.value.trim()});
    this.busy = what;
    this.buttons();
    this.status.textContent = `${what}: running…`;
    try {
      let job = await api.post(`/api/edit/${what}`, body);
      const start = performance.now();
      while (job.state === "running") {
        if (performance.now() - start > JOB_LIMIT_MS) throw new Error(`no result from the ${what} in ${JOB_LIMIT_MS / 1000} s`);
        await new Promise((r) => setTimeout(r, JOB_POLL_MS));
        job = await api.get("/api/edit/job");
      }
      this.finished(what, text, job.result || {});
    } catch (e) {
      this.status.textContent = `${what}: ${e.message}`;
      this.log(`${what}: ${e.message}`, "error");
    }
    this.busy = null;
    await this.load(true);
    if (what === "undo" || (what === "apply" && this.state && this.state.text !== text)) this.setText(this.state.text);
    this.buttons();
  }

  finished(what, text, result) {
    if (what === "test") {
      this.tested = {text, result};
      this.status.textContent = `gate ${result.passed ? "passed" : "failed"}: ${result.summary}`;
      this.showReport(result);
      return;
    }
    this.status.textContent = `${what}: ${result.result}${result.why ? ` — ${result.why}` : ""}`;
    if (result.gate && result.gate.configured) this.showReport(result.gate);
    if (result.errors && result.errors.length) this.showErrors(result);
  }

  // The gate's report: its summary, then each failing case and exploration as plc_cell test
  // gives it (the failing check, then the values and their last changes), and each mutant of
  // the changed lines that survived.
  showReport(gate) {
    this.report.textContent = "";
    const head = html("p", {class: gate.passed ? "gate-pass" : "gate-fail", id: "edit-gate"}, this.report,
                      `Gate ${gate.passed ? "passed" : "failed"} in ${Number(gate.seconds || 0).toFixed(2)} s: ${gate.summary}`);
    head.dataset.passed = gate.passed ? "true" : "false";
    const report = gate.report || {};
    for (const c of report.cases || []) {
      if (c.passed) continue;
      const d = html("div", {class: "gate-failure"}, this.report);
      html("strong", {}, d, `FAIL ${c.name}`);
      html("pre", {}, d, `${c.failure}\n${c.details || ""}`);
    }
    for (const e of report.explore || []) {
      if (!e.violated) continue;
      const d = html("div", {class: "gate-failure"}, this.report);
      html("strong", {}, d, `FAIL explore ${e.file} (seed ${e.seed}, ${e.runs} run(s))`);
      html("pre", {}, d, e.failure);
    }
    for (const m of (report.mutation && report.mutation.survived) || []) {
      const d = html("div", {class: "gate-failure"}, this.report);
      html("strong", {}, d, `FAIL mutant line ${m.line}: ${m.change}`);
      html("pre", {}, d, `survived (${m.why})${m.told_apart ? `\n${m.told_apart}` : ""}`);
    }
  }

  async loadLog() {
    let entries = [];
    try {
      entries = await api.get("/api/edit/log?last=50");
    } catch (e) {
      this.history.textContent = `the change log cannot be read: ${e.message}`;
      return;
    }
    this.history.textContent = "";
    if (!entries.length) html("p", {class: "muted"}, this.history, "No change yet.");
    const table = html("table", {class: "edit-log-table", id: "edit-log-table"}, this.history);
    for (const e of entries.slice().reverse()) {
      if (e.unreadable !== undefined) {
        html("td", {colspan: 5}, html("tr", {class: "error"}, table), `unreadable entry: ${e.unreadable}`);
        continue;
      }
      const tr = html("tr", {class: `log-${e.result}`}, table);
      tr.dataset.result = e.result;
      html("td", {}, tr, e.at || "");
      html("td", {}, tr, `${e.source}${e.undo ? " (undo)" : ""}`);
      html("td", {class: "result"}, tr, e.result);
      html("td", {class: "mono"}, tr, `${(e.old_hash || "").slice(0, 8)} → ${(e.new_hash || "").slice(0, 8)}`);
      const what = html("td", {}, tr);
      const gate = e.gate && e.gate.configured && !(e.why || "").includes(e.gate.summary) ? `gate: ${e.gate.summary}` : "";
      html("span", {}, what, [e.why, gate, e.reason && e.reason !== "undo" ? `reason: ${e.reason}` : ""]
        .filter(Boolean).join(" — "));
      if (e.diff) {
        const d = html("details", {}, what);
        html("summary", {}, d, "diff");
        html("pre", {}, d, e.diff);
      }
    }
  }

  // The tab became visible: CodeMirror measures itself only when shown.
  shown() {
    if (this.cm) this.cm.refresh();
  }
}
