// The coverage overlay: GET /api/coverage gives, per instruction in program order, what it
// did since coverage started (bit 0: evaluated with its rung off, bit 1: energised). The
// ladder colours by IL line, so the instructions are matched to lines: by the answer's own
// "lines" when it gives them, else by the ladder's IL listing, one entry per instruction in
// program order.

import * as api from "./api.js";

function instructionLines(ladderData) {
  const lines = [];
  for (const net of ladderData.networks || []) for (const l of net.il || []) lines.push(l.line);
  return lines;
}

// line -> seen bits, or null with the reason when there is no coverage.
export async function coverageByLine(ladderData) {
  const data = await api.coverage();
  if (!data.available) return {byLine: null, why: data.reason || "this source has no coverage"};
  const lines = Array.isArray(data.lines) ? data.lines : instructionLines(ladderData);
  const byLine = new Map();
  (data.seen || []).forEach((seen, i) => {
    const line = lines[i];
    if (line === undefined) return;
    byLine.set(line, (byLine.get(line) || 0) | seen);
  });
  return {byLine, why: ""};
}
