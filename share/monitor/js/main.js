// The monitor page: fetches the session, the ladder and the status, then lives on the
// WebSocket. Subscribes to the networks in view (IntersectionObserver) and to what the watch
// table and the trends show. After a drop it says so in a banner, keeps the last picture and
// starts again from the session when the server is back (a restarted cell has a new token
// and maybe a new program). A frame the server marks stale (a real PLC's link is down) gets
// the same banner, its values marked with their age and no power flow; a frame of a
// stopped cell draws no power flow either.

import * as api from "./api.js";
import {coverage} from "./coverage.js";
import {EditTab} from "./edit.js";
import {show} from "./format.js";
import {Ladder} from "./ladder.js";
import {Live} from "./live.js";
import {Log} from "./log.js";
import {ReplayBar} from "./replay.js";
import {modeRefusal, renderStatus} from "./status.js";
import {Trends} from "./trends.js";
import {Watch} from "./watch.js";

const $ = (id) => document.getElementById(id);
const page = {session: null, ladderData: null, status: null, visible: new Set(), coverage: false, replay: null,
              t_us: null, lost: "", stale: "", frames: 0};

const log = new Log($("log"));
// A cell of several (a line's) links back to the overview of all of them.
$("overview-link").hidden = !api.base;

// The address of a signal name of the program (the ladder's signals map address -> name).
function signalAddress(name) {
  const signals = (page.ladderData && page.ladderData.signals) || {};
  return Object.keys(signals).find((a) => signals[a] === name) || name;
}
// What the page logs itself (what never reached the server), on the cell's clock as last seen.
const addLog = (text, level) => log.add(text, level, page.t_us);
const watch = new Watch($("watch-panel"), {changed: () => resubscribe(), log: addLog, resolve: signalAddress});
const trends = new Trends($("trends-panel"), {changed: () => resubscribe(), log: addLog});
const ladder = new Ladder($("ladder"), async (address) => {
  if (await watch.add(address)) toast(`${address} added to the watch table`);
});
const edit = new EditTab($("edit-panel"), {log: addLog});
const observer = new IntersectionObserver(onVisibility, {root: null, rootMargin: "200px"});
const live = new Live({frame: onFrame, status: onStatus, log: onLogEvent, program: () => programChanged(),
                       open: onOpen, close: onClose, error: (m) => addLog(`server: ${m.error || m}`, "error")});

function toast(text) {
  const t = $("toast");
  t.textContent = text;
  t.hidden = false;
  clearTimeout(toast.timer);
  toast.timer = setTimeout(() => (t.hidden = true), 2000);
}

function rate() {
  return Number($("rate").value) || 10;
}

function resubscribe() {
  const networks = [...page.visible];
  // The server adds what the networks' drawing reads (ladder::addresses).
  live.subscribe(networks, [...watch.addresses(), ...trends.addresses()], rate());
}

function onVisibility(entries) {
  for (const e of entries) {
    const index = Number(e.target.dataset.network);
    if (e.isIntersecting) page.visible.add(index);
    else page.visible.delete(index);
  }
  resubscribe();
}

function describeSource(session, status) {
  const kind = session.kind || "live";
  const what = kind === "replay" ? "recording" : kind === "remote" ? "remote PLC" : "live cell";
  const note = (status && status.note) || (kind === "remote" ? "power flow computed from polled values" : "");
  $("kind").textContent = what;
  $("kind").dataset.kind = kind;
  $("source").textContent = `${session.source || ""}${note ? ` — ${note}` : ""}`;
  $("source").dataset.kind = kind;
  document.title = `${session.source || "plc_cell"} — monitor`;
}

async function loadSession() {
  const session = await api.session();
  page.session = session;
  api.setToken(session.token);
  if (session.rate_hz && !page.rateSet) $("rate").value = String(session.rate_hz);
  describeSource(session, page.status);
  if (session.kind === "replay") {
    if (!page.replay) page.replay = new ReplayBar($("replay"), addLog, () => [...watch.addresses(), ...trends.addresses()]);
    await page.replay.start();
  }
}

async function loadLadder() {
  const data = await api.ladder();
  page.ladderData = data;
  observer.disconnect();
  page.visible.clear();
  ladder.render(data);
  for (const e of ladder.nets) observer.observe(e.div);
  onSearch();
  if (page.coverage) await refreshCoverage();
  resubscribe();
}

// A new program is running (a change from this page, another, the service or the file).
async function programChanged() {
  await loadLadder();
  await loadEdit();
}

// The Edit tab keeps what is typed in it unless it still shows the program that ran before.
async function loadEdit() {
  try {
    const before = edit.state && edit.state.text;
    await edit.load(before !== undefined && before !== null && edit.text() !== before);
  } catch (e) {
    addLog(`edit: ${e.message}`, "error");
  }
}

async function loadStatus() {
  onStatus(await api.status());
}

function staleText(stale) {
  const age = stale.age_ms === null || stale.age_ms === undefined
    ? "no values have been read yet" : `the values shown are ${(stale.age_ms / 1000).toFixed(1)} s old`;
  return `No current values: ${stale.error}. ${age}; no power flow is drawn from them.`;
}

function onFrame(frame) {
  page.frames++;
  const values = frame.values || {};
  ladder.applyValues(values, (v) => show(v, "signed"));
  ladder.applyFlow(frame.flow);
  ladder.applyForced(frame.forced, values);
  ladder.applyFlowNote(frame.stale ? `Not current: ${staleText(frame.stale)}` : frame.no_flow || null, frame.stale);
  watch.applyValues(values, frame);
  if (!frame.stale) trends.addFrame(frame);
  if (page.replay) page.replay.frame(frame);
  page.stale = frame.stale ? staleText(frame.stale) : "";
  showBanner();
  page.modeWhy = frame.stale ? "the source cannot be read now" : frame.no_flow;
  if (frame.mode) setMode(frame.mode, page.modeWhy);
  if (!frame.stale) page.t_us = frame.t_us ?? page.t_us;
  const clock = $("clock");
  // A real PLC's scans are not seen: what its frames count are the monitor's polls.
  const counted = page.session && page.session.kind === "remote" ? "poll" : "scan";
  clock.textContent = `${counted} ${frame.scan ?? "–"}  t ${frame.t_us !== undefined ? (frame.t_us / 1e6).toFixed(3) : "–"} s`;
  clock.dataset.scan = frame.scan;
  clock.dataset.tUs = frame.t_us;
}

// why: what the server said of a mode it does not know (a link that is down, a TRi that
// reports no RUN/STOP).
function setMode(mode, why) {
  const m = $("mode");
  m.textContent = mode === "unknown" ? "RUN/STOP ?" : mode.toUpperCase();
  m.title = mode === "unknown" ? `not known: ${why || "the source cannot say"}` : "";
  m.className = `mode mode-${mode}`;
}

function onStatus(status) {
  const {type, ...rest} = status;
  page.status = rest;
  renderStatus($("status-panel"), rest);
  // A stale frame says the mode is not known; a status gathered meanwhile says no better.
  if (rest.mode && !page.stale) setMode(rest.mode, page.modeWhy);
  if (page.session) describeSource(page.session, rest);
  const button = $("mode-switch");
  const why = modeRefusal(rest);
  button.disabled = why !== "";
  button.title = why || `switch the cell to ${rest.mode === "run" ? "STOP" : "RUN"}`;
  button.textContent = rest.mode === "run" ? "STOP" : "RUN";
  if (page.coverage) refreshCoverage();
}

function onLogEvent(msg) {
  log.add(msg.text, /\(refused/.test(msg.text) ? "error" : "server", msg.t_us ?? null);
}

// One banner for what keeps the page from showing current values: its own connection lost,
// or the source's (a real PLC's link down).
function showBanner() {
  const text = page.lost || page.stale;
  const b = $("banner");
  if (b.textContent !== text) b.textContent = text;
  b.hidden = !text;
  document.body.classList.toggle("disconnected", Boolean(text));
}

function banner(text) {
  page.lost = text;
  showBanner();
}

async function onOpen() {
  try {
    await loadSession();
    await loadLadder();
    await loadStatus();
    await loadEdit();
    banner("");
    await watch.validate();
  } catch (e) {
    banner(`The server answered but the page could not load: ${e.message}. Retrying…`);
    setTimeout(onOpen, 1000);
  }
}

function onClose(why, delay) {
  banner(`Connection to the cell lost (${why}). Reconnecting in ${(delay / 1000).toFixed(1)} s… ` +
         "The page shows the last values it received.");
}

async function refreshCoverage(asked = false) {
  if (!page.ladderData) return;
  try {
    const {cov, why} = await coverage(page.ladderData);
    ladder.applyCoverage(cov);
    $("coverage-toggle").title = why || "coverage since the start: green energised, red evaluated only, grey never run";
    if (!cov && asked) toast(`no coverage: ${why}`);
  } catch (e) {
    addLog(`coverage: ${e.message}`, "error");
  }
}

async function toggleCoverage() {
  page.coverage = !page.coverage;
  const button = $("coverage-toggle");
  button.setAttribute("aria-pressed", String(page.coverage));
  button.classList.toggle("active", page.coverage);
  document.body.classList.toggle("coverage", page.coverage);
  if (page.coverage) await refreshCoverage(true);
  else ladder.applyCoverage(null);
}

async function switchMode() {
  const to = page.status && page.status.mode === "run" ? "stop" : "run";
  try {
    await api.setMode(to);  // the server logs it, accepted or refused, to every page
  } catch (e) {
    if (e.status === undefined) addLog(`mode ${to} (${e.message})`, "error");
    toast(e.message);
  }
}

function onSearch() {
  const q = $("search").value;
  const shown = ladder.search(q);
  $("search-count").textContent = q.trim() ? `${shown} of ${ladder.nets.length} networks` : "";
}

function showTab(id) {
  for (const b of document.querySelectorAll(".tabs button")) b.classList.toggle("active", b.dataset.tab === id);
  for (const s of document.querySelectorAll(".side .tab")) s.hidden = s.id !== id;
  if (id === "trends-panel") trends.resetGraph();
  document.body.classList.toggle("editing", id === "edit-panel");
  if (id === "edit-panel") edit.shown();
}

function wire() {
  for (const b of document.querySelectorAll(".tabs button")) b.addEventListener("click", () => showTab(b.dataset.tab));
  $("search").addEventListener("input", onSearch);
  $("coverage-toggle").addEventListener("click", toggleCoverage);
  $("mode-switch").addEventListener("click", switchMode);
  $("rate").addEventListener("change", () => {
    page.rateSet = true;
    resubscribe();
  });
}

wire();
live.connect();
// For the browser tests and the console: the page's parts.
window.plcMonitor = {page, ladder, watch, trends, live, edit};
