/**
 * Reading text formats (OBJ, ASCII PLY, file headers) straight from bytes. A mesh file
 * may be up to 1 GiB, more than a JavaScript string can hold, so the parsers never
 * decode a whole file: they scan bytes and convert one token at a time.
 */

export const enum Byte {
  Tab = 9,
  LineFeed = 10,
  CarriageReturn = 13,
  Space = 32,
  Plus = 43,
  Minus = 45,
  Dot = 46,
  Slash = 47,
  Zero = 48,
  Nine = 57,
  UpperE = 69,
  LowerE = 101,
}

/** Space, tab, carriage return, vertical tab or form feed: separators inside a line. */
export function isBlank(c: number): boolean {
  return c === Byte.Space || c === Byte.Tab || c === Byte.CarriageReturn || c === 11 || c === 12;
}

/** Index of the end of the line that starts at `start` (the '\n' or the end of the bytes). */
export function lineEnd(bytes: Uint8Array, start: number): number {
  const i = bytes.indexOf(Byte.LineFeed, start);
  return i < 0 ? bytes.length : i;
}

/** Index of the first non-blank byte at or after `i`, before `end`. */
export function skipBlanks(bytes: Uint8Array, i: number, end: number): number {
  while (i < end && isBlank(bytes[i])) i++;
  return i;
}

/** Index just past the token that starts at `i`. */
export function tokenEnd(bytes: Uint8Array, i: number, end: number): number {
  while (i < end && !isBlank(bytes[i])) i++;
  return i;
}

/** Whether bytes[start, end) spell the ASCII word `word`. */
export function bytesEqual(bytes: Uint8Array, start: number, end: number, word: string): boolean {
  if (end - start !== word.length) return false;
  for (let i = 0; i < word.length; i++) if (bytes[start + i] !== word.charCodeAt(i)) return false;
  return true;
}

/** bytes[start, end) as a string, for short tokens only (Latin-1: one char per byte). */
export function bytesToString(bytes: Uint8Array, start: number, end: number): string {
  let s = '';
  for (let i = start; i < end; i++) s += String.fromCharCode(bytes[i]);
  return s;
}

/**
 * A token from a file, quoted for a message: at most ~40 characters, printable ASCII
 * kept and anything else written as \xNN, so a message stays one printable line.
 */
export function quoteBytes(bytes: Uint8Array, start: number, end: number): string {
  const limit = Math.min(end, start + 40);
  let s = '';
  for (let i = start; i < limit; i++) {
    const c = bytes[i];
    if (c === 0x22 || c === 0x5c) s += '\\' + String.fromCharCode(c);
    else if (c >= 0x20 && c < 0x7f) s += String.fromCharCode(c);
    else s += '\\x' + c.toString(16).padStart(2, '0');
  }
  return `"${s}${end > limit ? '...' : ''}"`;
}

const POW10_EXACT = Array.from({ length: 23 }, (_, i) => Number(`1e${i}`));

/**
 * The decimal number spelled by bytes[start, end) ([+-]digits[.digits][(e|E)[+-]digits],
 * at least one digit in the mantissa), correctly rounded as `Number()` would; NaN for
 * anything else (including "inf", "nan" and hexadecimal). With at most 15 significant
 * digits and a power of ten up to 10^22 the value is one correctly rounded operation on
 * exact operands (Clinger's fast path); otherwise the token goes through `Number()`.
 */
export function parseDecimal(bytes: Uint8Array, start: number, end: number): number {
  let i = start;
  let negative = false;
  if (i < end && (bytes[i] === Byte.Minus || bytes[i] === Byte.Plus)) {
    negative = bytes[i] === Byte.Minus;
    i++;
  }
  let mantissa = 0;
  let digits = 0; // significant digits taken into the mantissa
  let scale = 0; // power of ten to apply
  let any = false;
  let exact = true;
  while (i < end && bytes[i] >= Byte.Zero && bytes[i] <= Byte.Nine) {
    any = true;
    if (digits < 15) {
      mantissa = mantissa * 10 + (bytes[i] - Byte.Zero);
      if (mantissa !== 0) digits++;
    } else {
      exact = false;
    }
    i++;
  }
  if (i < end && bytes[i] === Byte.Dot) {
    i++;
    while (i < end && bytes[i] >= Byte.Zero && bytes[i] <= Byte.Nine) {
      any = true;
      if (digits < 15) {
        mantissa = mantissa * 10 + (bytes[i] - Byte.Zero);
        if (mantissa !== 0) digits++;
        scale--;
      } else {
        exact = false;
      }
      i++;
    }
  }
  if (!any) return NaN;
  if (i < end && (bytes[i] === Byte.LowerE || bytes[i] === Byte.UpperE)) {
    i++;
    let expNegative = false;
    if (i < end && (bytes[i] === Byte.Minus || bytes[i] === Byte.Plus)) {
      expNegative = bytes[i] === Byte.Minus;
      i++;
    }
    let e = 0;
    let expDigits = 0;
    while (i < end && bytes[i] >= Byte.Zero && bytes[i] <= Byte.Nine) {
      if (e < 100000) e = e * 10 + (bytes[i] - Byte.Zero);
      expDigits++;
      i++;
    }
    if (expDigits === 0) return NaN;
    scale += expNegative ? -e : e;
  }
  if (i !== end) return NaN;
  if (exact && scale >= -22 && scale <= 22) {
    const v = scale < 0 ? mantissa / POW10_EXACT[-scale] : mantissa * POW10_EXACT[scale];
    return negative ? -v : v;
  }
  return Number(bytesToString(bytes, start, end));
}

/** A non-negative decimal integer (no sign, no point), or NaN. */
export function parseUnsigned(bytes: Uint8Array, start: number, end: number): number {
  if (start === end) return NaN;
  let v = 0;
  for (let i = start; i < end; i++) {
    const c = bytes[i];
    if (c < Byte.Zero || c > Byte.Nine) return NaN;
    v = v * 10 + (c - Byte.Zero);
  }
  return v;
}

/** An optionally signed decimal integer, or NaN. */
export function parseInteger(bytes: Uint8Array, start: number, end: number): number {
  if (start < end && (bytes[start] === Byte.Minus || bytes[start] === Byte.Plus)) {
    const v = parseUnsigned(bytes, start + 1, end);
    return bytes[start] === Byte.Minus ? -v : v;
  }
  return parseUnsigned(bytes, start, end);
}
