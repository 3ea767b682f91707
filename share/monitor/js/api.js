// The server's HTTP API (docs/monitor-api.md): JSON in and out, the session token on every
// request that changes something. A refused request rejects with the server's own message.

let token = "";

// The page's cell: "" for a lone cell's page at /, "/cell/NAME" for a cell of several
// (a line's), whose API is under that path (docs/monitor-api.md).
export const base = (location.pathname.match(/^\/cell\/[^/]+/) || [""])[0];

export function setToken(t) {
  token = t || "";
}

async function call(method, path, body) {
  const headers = {};
  if (body !== undefined) headers["Content-Type"] = "application/json";
  if (method !== "GET") headers["X-Plc-Token"] = token;
  let response;
  try {
    response = await fetch(base + path, {method, headers, cache: "no-store",
                                  body: body === undefined ? undefined : JSON.stringify(body)});
  } catch (e) {
    throw new Error(`${method} ${path}: the server did not answer (${e.message})`);
  }
  let data = null;
  try {
    data = await response.json();
  } catch (e) {
    data = null;
  }
  if (!response.ok) {
    const why = data && data.error ? data.error : `HTTP ${response.status}`;
    const err = new Error(why);
    err.status = response.status;
    throw err;
  }
  return data;
}

// Whether every name or address can be read: "" or the server's reason.
export async function unreadable(names) {
  try {
    if (names.length) await read(names);
    return "";
  } catch (e) {
    return e.message;
  }
}

export const get = (path) => call("GET", path);
export const post = (path, body) => call("POST", path, body);

export const session = () => get("/api/session");
export const ladder = () => get("/api/ladder");
export const status = () => get("/api/status");
export const coverage = () => get("/api/coverage");
export const replayState = () => get("/api/replay");
export const replayMove = (body) => post("/api/replay", body);
export const read = (names) => get(`/api/read?a=${encodeURIComponent(names.join(","))}`);
// {name: {write, force}}: why the server would refuse each ("" = it would not).
export const access = (names) => get(`/api/access?a=${encodeURIComponent(names.join(","))}`);
export const write = (address, values) => post("/api/write", {address, values});
export const force = (address, action) => post("/api/force", {address, action});
export const setMode = (mode) => post("/api/mode", {mode});
