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
