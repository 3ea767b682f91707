// A recorded run (session kind "replay"): a time slider over begin..end with the failure
// instant marked and the failing check's text shown, and steps by scan or by event (a
// change of the program's own addresses or of what the page watches: the server knows the
// first, the page says the second). Every move is a POST /api/replay; the server then
// pushes the frame of the new instant, which the ladder, watch and trends show.

import * as api from "./api.js";
import {html} from "./dom.js";

function seconds(t_us) {
  return `${(t_us / 1e6).toFixed(3)} s`;
}

export class ReplayBar {
  // watched(): the addresses the page shows besides the ladder (watch table, trends).
  constructor(root, log, watched = () => []) {
    this.root = root;
    this.log = log;
    this.watched = watched;
    this.state = null;
    this.moving = false;
  }

  async start() {
    this.root.hidden = false;
    this.build();
    await this.refresh();
  }

  build() {
    this.root.textContent = "";
    const steps = [["◀◀ event", "event", -1], ["◀ scan", "scan", -1], ["scan ▶", "scan", 1], ["event ▶▶", "event", 1]];
    const back = html("span", {class: "steps"}, this.root);
    for (const [label, step, n] of steps.slice(0, 2))
      html("button", {class: `step-${step}-${n < 0 ? "back" : "fwd"}`, onclick: () => this.step(step, n)}, back, label);
    const track = html("div", {class: "track"}, this.root);
    this.slider = html("input", {type: "range", id: "replay-slider", min: 0, max: 1000, step: 1, value: 0}, track);
    this.failure = html("div", {class: "failure-mark", id: "replay-failure", title: "the failure", hidden: ""}, track);
    this.slider.addEventListener("change", () => this.seek(Number(this.slider.value)));
    const fwd = html("span", {class: "steps"}, this.root);
    for (const [label, step, n] of steps.slice(2))
      html("button", {class: `step-${step}-${n < 0 ? "back" : "fwd"}`, onclick: () => this.step(step, n)}, fwd, label);
    this.cursor = html("span", {class: "cursor", id: "replay-cursor"}, this.root, "");
    this.jump = html("button", {id: "replay-to-failure", hidden: "", onclick: () => this.toFailure()}, this.root,
                     "to the failure");
    // Its own line under the slider (the bar's stylesheet is the page's: styled here).
    this.root.style.flexWrap = "wrap";
    this.failureText = html("div", {class: "failure-text", id: "replay-failure-text", hidden: "",
                                    style: "flex-basis: 100%; color: #b91c1c; font-family: monospace; white-space: pre-wrap"},
                            this.root, "");
  }

  step(step, n) {
    return this.move(step === "event" ? {step, n, watch: [...new Set(this.watched())]} : {step, n});
  }

  async refresh() {
    try {
      this.show(await api.replayState());
    } catch (e) {
      this.log(`replay: ${e.message}`, "error");
    }
  }

  show(state) {
    if (!state || state.begin_us === undefined) return;
    this.state = state;
    const span = Math.max(1, state.end_us - state.begin_us);
    this.slider.min = state.begin_us;
    this.slider.max = state.end_us;
    this.slider.step = Math.max(1, Math.floor(span / 10000));
    if (!this.moving) this.slider.value = state.cursor_us;
    this.cursor.textContent = `${seconds(state.cursor_us)} of ${seconds(state.begin_us)}..${seconds(state.end_us)}`;
    this.cursor.dataset.cursorUs = state.cursor_us;
    const failure = state.failure_us;
    this.failure.hidden = failure === null || failure === undefined;
    this.jump.hidden = this.failure.hidden;
    this.failureText.hidden = this.failure.hidden;
    if (!this.failure.hidden) {
      this.failure.style.left = `${(100 * (failure - state.begin_us)) / span}%`;
      this.failure.title = `the failure at ${seconds(failure)}`;
      this.failureText.textContent = `failed at ${seconds(failure)}: ${state.failure || "(the recording keeps no text)"}`;
    }
  }

  async move(body) {
    this.moving = true;
    try {
      const answer = await api.replayMove(body);
      this.moving = false;
      if (answer && answer.begin_us !== undefined) this.show(answer);
      else await this.refresh();
    } catch (e) {
      this.moving = false;
      this.log(`replay: ${e.message}`, "error");
    }
  }

  seek(t_us) {
    return this.move({seek_us: Math.round(t_us)});
  }

  toFailure() {
    if (this.state && this.state.failure_us !== null && this.state.failure_us !== undefined)
      this.seek(this.state.failure_us);
  }

  // A frame of the recording: the cursor is at its instant.
  frame(frame) {
    if (!this.state || frame.t_us === undefined) return;
    if (frame.t_us !== this.state.cursor_us) this.show({...this.state, cursor_us: frame.t_us});
  }
}
