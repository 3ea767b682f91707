// Watch tables: named lists of addresses or signal names, one format per row, with writing
// and forcing through the API. A row's write and force controls are disabled, the reason in
// their tooltip, where the server would refuse them (GET /api/access); a forced point is
// marked with the state it is held in, and values that are not current with their age. The
// tables are kept in localStorage and can be downloaded and loaded again as a JSON file:
// {"tables": [{"name", "rows": [{"address", "format"}]}]}.

import * as api from "./api.js";
import {FORMATS, isBit, parse, readAddress, show} from "./format.js";
import {addForm, download, html} from "./dom.js";

// Each cell of a line keeps its own tables: its unqualified names are its own.
const STORE = "plc_cell.monitor.watch" + api.base;

function validTables(data) {
  if (!data || !Array.isArray(data.tables)) throw new Error('a watch file holds {"tables": [...]}');
  return data.tables.map((t, i) => {
    if (!t || !Array.isArray(t.rows)) throw new Error(`table ${i + 1} has no "rows" list`);
    return {name: String(t.name || `table ${i + 1}`),
            rows: t.rows.filter((r) => r && r.address).map((r) => ({
              address: String(r.address).trim(), format: FORMATS.includes(r.format) ? r.format : "unsigned"}))};
  });
}

export class Watch {
  constructor(root, {changed, log, resolve}) {
    this.root = root;
    this.resolve = resolve;  // signal name -> address
    this.changed = changed;  // the subscription must change
    this.log = log;          // (text, level) into the log panel
    this.values = {};
    this.frame = {forced: [], stale: null};
    this.bad = new Map();  // read address -> why the cell cannot read it
    this.access = new Map();  // read address -> {write, force}: why not ("" = allowed)
    this.tables = this.load();
    this.current = 0;
    this.build();
  }

  load() {
    try {
      const saved = localStorage.getItem(STORE);
      if (saved) return validTables(JSON.parse(saved));
    } catch (e) {
      console.warn("watch tables in localStorage ignored:", e.message);
    }
    return [{name: "watch 1", rows: []}];
  }

  save() {
    localStorage.setItem(STORE, JSON.stringify({tables: this.tables}));
  }

  table() {
    return this.tables[this.current];
  }

  build() {
    this.root.textContent = "";
    const bar = html("div", {class: "bar"}, this.root);
    this.picker = html("select", {id: "watch-table", title: "watch table",
                                  onchange: () => this.select(Number(this.picker.value))}, bar);
    html("button", {onclick: () => this.newTable()}, bar, "New table");
    html("button", {onclick: () => this.deleteTable()}, bar, "Delete table");
    html("button", {id: "watch-download", onclick: () => this.download()}, bar, "Download");
    const upload = html("input", {type: "file", accept: ".json,application/json", id: "watch-upload"}, bar);
    upload.addEventListener("change", () => upload.files[0] && this.upload(upload.files[0]));
    addForm(this.root, "watch", "D0, X1, temp_pv ...", (a) => this.add(a));
    const table = html("table", {class: "watch", id: "watch"}, this.root);
    const head = html("tr", {}, html("thead", {}, table));
    for (const h of ["address", "format", "value", "write", "force", ""]) html("th", {}, head, h);
    head.lastChild.title = "remove";
    this.body = html("tbody", {}, table);
    this.redraw();
  }

  redraw() {
    this.picker.textContent = "";
    this.tables.forEach((t, i) => html("option", {value: i}, this.picker, t.name));
    this.picker.value = this.current;
    this.body.textContent = "";
    this.cells = [];
    this.table().rows.forEach((row, i) => this.cells.push(this.renderRow(row, i)));
    this.applyAccess();
    this.applyValues(this.values, this.frame);
  }

  renderRow(row, i) {
    const tr = html("tr", {}, this.body);
    tr.dataset.address = row.address;
    const name = html("td", {class: "address"}, tr, row.address);
    const why = this.bad.get(this.read(row));
    if (why) {
      tr.classList.add("invalid");
      name.title = why;
    }
    const fmt = html("select", {class: "format"}, html("td", {}, tr));
    for (const f of FORMATS) html("option", {value: f}, fmt, f);
    fmt.value = row.format;
    fmt.addEventListener("change", () => this.setFormat(i, fmt.value));
    const value = html("td", {class: "value"}, tr);
    const wcell = html("td", {}, tr);
    const form = html("form", {class: "write"}, wcell);
    const input = html("input", {class: "write-value", size: 6, placeholder: "value"}, form);
    const wbutton = html("button", {type: "submit", class: "write-button"}, form, "Write");
    form.addEventListener("submit", (ev) => {
      ev.preventDefault();
      this.write(row, input.value);
    });
    const fcell = html("td", {class: "force"}, tr);
    const force = [];
    if (isBit(row.address) || !/^[A-Z]+\d+$/i.test(row.address)) {
      for (const [action, label] of [["on", "on"], ["off", "off"], ["release", "free"]])
        force.push(html("button", {class: `force-${action}`, title: `force ${action}`,
                                   onclick: () => this.force(row.address, action)}, fcell, label));
    }
    html("button", {class: "remove", title: "remove the row", onclick: () => this.remove(i)}, html("td", {}, tr), "×");
    return {row, tr, value, write: [input, wbutton], force};
  }

  // Greys out what the server would refuse, with its reason as the tooltip.
  applyAccess() {
    for (const {row, write, force} of this.cells) {
      const a = this.access.get(this.read(row));
      const set = (nodes, why, title) => {
        for (const n of nodes) {
          n.disabled = Boolean(why);
          n.title = why || title(n);
        }
      };
      set(write, a ? a.write : "", () => "write the value in the row's format");
      set(force, a ? a.force : "", (n) => n.className.replace("force-", "force "));
    }
  }

  // A name or address the cell cannot read is refused here, with the server's reason: in
  // the subscription it would make the server refuse the whole list.
  async add(address) {
    const why = await api.unreadable([address]);
    if (why) {
      this.log(`watch ${address}: ${why}`, "error");
      return false;
    }
    const rows = this.table().rows;
    if (!rows.some((r) => r.address === address)) rows.push({address, format: "unsigned"});
    this.commit();
    await this.checkAccess([address]);
    return true;
  }

  // Marks the rows this cell cannot read (tables saved for another cell); they stay in the
  // table but out of the subscription.
  async validate() {
    const bad = new Map();
    const wanted = this.table().rows.map((r) => this.read(r));
    if (await api.unreadable(wanted)) {
      for (const a of wanted) {
        const why = await api.unreadable([a]);
        if (why) bad.set(a, why);
      }
    }
    await this.checkAccess(wanted.filter((a) => !bad.has(a)));
    // Redrawn only when the verdict changed: a redraw replaces the rows being typed in.
    if (JSON.stringify([...bad]) === JSON.stringify([...this.bad])) return;
    this.bad = bad;
    this.redraw();
    this.changed();
  }

  async checkAccess(addresses) {
    if (!addresses.length) return;
    try {
      const answer = await api.access(addresses);
      for (const [a, why] of Object.entries(answer)) this.access.set(a, why);
    } catch (e) {
      this.log(`watch: ${e.message}`, "error");
    }
    this.applyAccess();
  }

  remove(i) {
    this.table().rows.splice(i, 1);
    this.commit();
  }

  async setFormat(i, format) {
    this.table().rows[i].format = format;
    this.commit();
    await this.validate();
  }

  commit() {
    this.save();
    this.redraw();
    this.changed();
  }

  select(i) {
    this.current = Math.max(0, Math.min(i, this.tables.length - 1));
    this.redraw();
    this.changed();
    this.validate();
  }

  newTable() {
    this.tables.push({name: `watch ${this.tables.length + 1}`, rows: []});
    this.current = this.tables.length - 1;
    this.commit();
  }

  deleteTable() {
    this.tables.splice(this.current, 1);
    if (!this.tables.length) this.tables.push({name: "watch 1", rows: []});
    this.current = 0;
    this.commit();
  }

  download() {
    download("watch-tables.json", JSON.stringify({tables: this.tables}, null, 2), "application/json");
  }

  async upload(file) {
    try {
      this.tables = validTables(JSON.parse(await file.text()));
      this.current = 0;
      this.commit();
      await this.validate();
      this.log(`loaded ${this.tables.length} watch table(s) from ${file.name}`, "info");
    } catch (e) {
      this.log(`${file.name}: ${e.message}`, "error");
    }
  }

  read(row) {
    return readAddress(row.address, row.format, this.resolve);
  }

  // What the subscription must read for the current table.
  addresses() {
    return this.table().rows.map((r) => this.read(r)).filter((a) => !this.bad.has(a));
  }

  // A frame's values, its forced points and whether it is stale ({age_ms, error}).
  applyValues(values, frame = {}) {
    this.values = values;
    this.frame = frame;
    const forced = new Set(frame.forced || []);
    const stale = frame.stale || null;
    const age = stale ? (stale.age_ms === null ? "never read" : `${(stale.age_ms / 1000).toFixed(1)} s old`) : "";
    for (const {row, tr, value} of this.cells) {
      const key = this.read(row);
      const held = forced.has(key);
      const on = Number(values[key]) ? "ON" : "OFF";
      const text = key in values ? show(values[key], row.format) : "";
      const note = [held ? `forced ${on}` : "", age].filter(Boolean).join(", ");
      const shown = note ? `${text} (${note})` : text;
      if (value.textContent !== shown) value.textContent = shown;
      tr.classList.toggle("forced", held);
      tr.dataset.forced = held ? on.toLowerCase() : "";
      value.classList.toggle("stale", Boolean(stale));
      value.title = stale ? `not current: ${age} (${stale.error})` : "";
    }
  }

  async write(row, text) {
    const address = this.read(row);
    let v;
    try {
      v = parse(text, row.format);
    } catch (e) {
      this.log(`write ${address} (refused here: ${e.message})`, "error");
      return;
    }
    await this.ask(`write ${address} = ${text.trim()}`, () => api.write(address, [v]));
  }

  async force(address, action) {
    await this.ask(`force ${address} ${action}`, () => api.force(address, action));
  }

  // The server logs every change it is asked for, to every page: only a request it never
  // answered is logged here.
  async ask(what, request) {
    try {
      await request();
    } catch (e) {
      if (e.status === undefined) this.log(`${what} (${e.message})`, "error");
    }
  }
}
