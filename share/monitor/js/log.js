// The log panel: every change any page asked for (write, force, RUN/STOP), accepted or
// refused, as the server reports it to every page, and what the server says about the
// source (a link lost and back); this page adds only what never reached the server. Each
// line is stamped with the cell's clock (the recording's, or for a real PLC the monitor's
// since it started); newest first, bounded.

import {html} from "./dom.js";

const KEEP = 500;

export class Log {
  constructor(list) {
    this.list = list;
  }

  // level: "error" (refused or failed), "server" (the server's log event), "info".
  // t_us: the cell's clock, null when not known.
  add(text, level = "info", t_us = null) {
    const li = html("li", {class: level});
    html("span", {class: "when"}, li, t_us === null || t_us === undefined ? "–" : `${(t_us / 1e6).toFixed(3)} s`);
    html("span", {class: "text"}, li, text);
    this.list.prepend(li);
    while (this.list.children.length > KEEP) this.list.lastChild.remove();
  }
}
