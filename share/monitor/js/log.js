// The log panel: every write and force, this page's own (with the server's answer) and every
// page's (the server's log events), newest first, bounded.

import {html} from "./dom.js";

const KEEP = 500;

export class Log {
  constructor(list) {
    this.list = list;
  }

  // level: "own" (this page's accepted request), "error" (refused), "server" (a log event), "info".
  add(text, level = "info", t_us = null) {
    const li = html("li", {class: level});
    const when = t_us === null ? new Date().toLocaleTimeString() : `${(t_us / 1e6).toFixed(3)} s`;
    html("span", {class: "when"}, li, when);
    html("span", {class: "text"}, li, text);
    this.list.prepend(li);
    while (this.list.children.length > KEEP) this.list.lastChild.remove();
  }
}
