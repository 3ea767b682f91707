// Small helpers for building SVG and HTML nodes.

const SVG_NS = "http://www.w3.org/2000/svg";

export function svg(tag, attrs = {}, parent = null, text = null) {
  const node = document.createElementNS(SVG_NS, tag);
  for (const [k, v] of Object.entries(attrs)) node.setAttribute(k, v);
  if (text !== null) node.textContent = text;
  if (parent) parent.appendChild(node);
  return node;
}

export function html(tag, attrs = {}, parent = null, text = null) {
  const node = document.createElement(tag);
  for (const [k, v] of Object.entries(attrs)) {
    if (k === "class") node.className = v;
    else if (k.startsWith("on")) node.addEventListener(k.slice(2), v);
    else node.setAttribute(k, v);
  }
  if (text !== null) node.textContent = text;
  if (parent) parent.appendChild(node);
  return node;
}

// Hands the browser a file to save.
export function download(name, text, type) {
  const a = html("a", {href: URL.createObjectURL(new Blob([text], {type})), download: name}, document.body);
  a.click();
  setTimeout(() => URL.revokeObjectURL(a.href), 1000);
  a.remove();
}

// A form that adds names: "<prefix>-add" for the field, "<prefix>-add-form" for the form;
// onAdd gets each name of a list separated by spaces, commas or semicolons.
export function addForm(parent, prefix, placeholder, onAdd) {
  const form = html("form", {class: "add", id: `${prefix}-add-form`}, parent);
  const input = html("input", {id: `${prefix}-add`, placeholder, size: 24}, form);
  html("button", {type: "submit"}, form, "Add");
  form.addEventListener("submit", async (ev) => {
    ev.preventDefault();
    const names = input.value.split(/[\s,;]+/).filter(Boolean);
    input.value = "";
    for (const a of names) await onAdd(a);  // in the order given
  });
}

// Brings a table body's rows in line with items, one row per key, in the items' order. A row
// whose key stays is kept and only its cells' text changes: a link or a selection under the
// user's pointer survives a redraw (a body rebuilt at every poll loses the click that lands
// between two polls). build(item) makes a new row's cells; fill(tr, item) sets every value.
export function keyedRows(body, items, keyOf, build, fill) {
  const old = new Map([...body.children].map((tr) => [tr.dataset.key, tr]));
  items.forEach((item, i) => {
    const key = keyOf(item);
    let tr = old.get(key);
    old.delete(key);
    if (!tr) {
      tr = html("tr", {"data-key": key});
      build(tr, item);
    }
    if (body.children[i] !== tr) body.insertBefore(tr, body.children[i] || null);
    fill(tr, item);
  });
  for (const tr of old.values()) tr.remove();
}

// Sets a node's text only when it differs, so an unchanged value is not redrawn.
export function setText(node, text) {
  if (node.textContent !== text) node.textContent = text;
}
