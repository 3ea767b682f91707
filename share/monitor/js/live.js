// The WebSocket /api/live: frames, status, log and program events in; the subscription out.
// It reconnects by itself after a drop (a cell restart, a network hiccup), with a growing
// pause between attempts, and sends the current subscription again on every connection.

import {base} from "./api.js";

export class Live {
  constructor(handlers) {
    this.handlers = handlers;  // {frame, status, log, program, open, close}
    this.subscription = {networks: [], watch: [], rate_hz: 10};
    this.socket = null;
    this.delay = 250;
    this.timer = null;
  }

  url() {
    const scheme = location.protocol === "https:" ? "wss:" : "ws:";
    return `${scheme}//${location.host}${base}/api/live`;
  }

  connect() {
    clearTimeout(this.timer);
    let socket;
    try {
      socket = new WebSocket(this.url());
    } catch (e) {
      this.retry(e.message);
      return;
    }
    this.socket = socket;
    socket.onopen = () => {
      this.delay = 250;
      this.sendSubscription();
      this.handlers.open && this.handlers.open();
    };
    socket.onmessage = (ev) => this.dispatch(ev.data);
    socket.onclose = (ev) => {
      if (this.socket !== socket) return;
      this.socket = null;
      this.retry(ev.reason || `connection closed (code ${ev.code})`);
    };
    socket.onerror = () => {};
  }

  retry(why) {
    this.handlers.close && this.handlers.close(why, this.delay);
    this.timer = setTimeout(() => this.connect(), this.delay);
    this.delay = Math.min(this.delay * 2, 4000);
  }

  dispatch(text) {
    let msg;
    try {
      msg = JSON.parse(text);
    } catch (e) {
      return;
    }
    const handler = this.handlers[msg.type];
    if (handler) handler(msg);
    else if (msg.error && this.handlers.error) this.handlers.error(msg.error);
  }

  connected() {
    return this.socket !== null && this.socket.readyState === WebSocket.OPEN;
  }

  // Sent only when it changed: the server keeps the last one.
  subscribe(networks, watch, rate_hz) {
    const next = {networks: [...networks].sort((a, b) => a - b), watch: [...new Set(watch)].slice(0, 512),
                  rate_hz};
    if (JSON.stringify(next) === JSON.stringify(this.subscription)) return;
    this.subscription = next;
    this.sendSubscription();
  }

  sendSubscription() {
    if (this.connected()) this.socket.send(JSON.stringify({subscribe: this.subscription}));
  }
}
