// The coverage overlay: GET /api/coverage gives, per instruction in program order, what it
// did since coverage started (bit 0: evaluated with its rung off, bit 1: energised). Drawn
// elements carry their instruction's index; the IL listing of an undrawable network is
// coloured by line, the instructions matched to lines by the answer's own "lines" when it
// gives them, else by the ladder's IL listings, one entry per instruction in program order.

import * as api from "./api.js";

function instructionLines(ladderData) {
  const lines = [];
  for (const net of ladderData.networks || []) for (const l of net.il || []) lines.push(l.line);
  return lines;
}

// {seen: per instruction, byLine: line -> seen bits}, or null with the reason when there is no coverage.
export async function coverage(ladderData) {
  const data = await api.coverage();
  if (!data.available) return {cov: null, why: data.reason || "this source has no coverage"};
  const lines = Array.isArray(data.lines) ? data.lines : instructionLines(ladderData);
  const seen = data.seen || [];
  const byLine = new Map();
  seen.forEach((bits, i) => {
    const line = lines[i];
    if (line !== undefined) byLine.set(line, (byLine.get(line) || 0) | bits);
  });
  return {cov: {seen, byLine}, why: ""};
}
