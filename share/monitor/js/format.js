// Watch-table formats. The server gives every value unsigned, as the PLC holds it (a 16-bit
// register 0..65535, a 32-bit one 0..2^32-1); the formats read and write those bits.
// "32-bit" and "float" read the register as its 32-bit pair: the D-prefixed address
// (R0 -> DR0, D10 -> DD10), as the FATEK instructions and the API name a double word.

export const FORMATS = ["signed", "unsigned", "hex", "32-bit", "float"];

const BIT = /^(X|Y|M|S|T|C)\d+$/i;

export function isBit(address) {
  return BIT.test(address);
}

export function isWide(format) {
  return format === "32-bit" || format === "float";
}

// What the subscription asks for to show `address` in `format`; a signal name is first
// turned into its address by `resolve` (the program's signals) for the wide formats.
export function readAddress(address, format, resolve = (a) => a) {
  if (!isWide(format)) return address;
  const a = /^[A-Z]+\d+$/i.test(address) ? address : resolve(address);
  if (isBit(a) || /^D[A-Z]/i.test(a) || !/^[A-Z]+\d+$/i.test(a)) return a;
  return `D${a}`;
}

function floatOf(bits) {
  const view = new DataView(new ArrayBuffer(4));
  view.setUint32(0, bits >>> 0);
  return view.getFloat32(0);
}

function bitsOf(f) {
  const view = new DataView(new ArrayBuffer(4));
  view.setFloat32(0, f);
  return view.getUint32(0);
}

export function show(value, format) {
  if (value === undefined || value === null) return "";
  const v = Number(value);
  switch (format) {
    case "signed":
      return String(v > 0xffff ? v | 0 : v >= 0x8000 ? v - 0x10000 : v);
    case "hex":
      return "0x" + (v >>> 0).toString(16).toUpperCase().padStart(v > 0xffff ? 8 : 4, "0");
    case "32-bit":
      return String(v | 0);
    case "float": {
      const f = floatOf(v);
      return Number.isFinite(f) ? String(Number(f.toPrecision(7))) : String(f);
    }
    default:
      return String(v >>> 0);
  }
}

// The value to write for what the user typed, in the row's format; throws saying why.
export function parse(text, format) {
  const t = text.trim();
  if (!t) throw new Error("no value given");
  if (format === "float") {
    const f = Number(t);
    if (!Number.isFinite(f)) throw new Error(`"${t}" is not a number`);
    return bitsOf(f);
  }
  const v = /^[-+]?0x[0-9a-f]+$/i.test(t) ? (t.startsWith("-") ? -1 : 1) * parseInt(t.replace(/^[-+]/, ""), 16)
          : /^[-+]?\d+$/.test(t) ? parseInt(t, 10) : NaN;
  if (!Number.isFinite(v)) throw new Error(`"${t}" is not an integer`);
  // The server stores negative values as two's complement and names the range it refuses.
  return v;
}
