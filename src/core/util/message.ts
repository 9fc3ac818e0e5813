/**
 * Printable messages about untrusted input (docs/scene-format.md, "Bad input"): every
 * message is one printable line and quotes at most ~80 characters of any value or key
 * from a file. A key or string from a file may hold terminal escape sequences, NUL bytes,
 * line breaks, bidirectional overrides or 100,000 characters; echoed raw, they clear a
 * terminal, forge a second line of output or drown the message. Every quoted value goes
 * through `quote` (or `sanitize`), and the final writer of a message applies
 * `printableLine` as a last guard.
 */

/** How many characters of a value a message shows, by default. */
export const QUOTE_MAX = 80;

/**
 * Characters that are shown escaped: controls (C0, DEL, C1), format characters (bidi
 * overrides, zero-width joiners, the BOM, tag characters), line and paragraph separators,
 * private-use characters and lone surrogates. Everything else is printable as it is.
 */
const UNPRINTABLE = /[\p{Cc}\p{Cf}\p{Zl}\p{Zp}\p{Co}\p{Cs}]/u;

const SHORT_ESCAPES: Record<string, string> = {
  '\n': '\\n',
  '\r': '\\r',
  '\t': '\\t',
  '\b': '\\b',
  '\f': '\\f',
};

function escapeChar(ch: string): string {
  const short = SHORT_ESCAPES[ch];
  if (short !== undefined) return short;
  const code = ch.codePointAt(0)!;
  return code <= 0xffff ? `\\u${code.toString(16).padStart(4, '0')}` : `\\u{${code.toString(16)}}`;
}

/**
 * The text with every unprintable character escaped (`\n`, `\u001b`, `\u{e0041}`), cut
 * to about `max` characters of output (never inside an escape or a surrogate pair) and
 * marked `...` when cut. With `quoteMarks`, `"` and `\` are escaped as well, so that the
 * quoted form is unambiguous. Work is bounded by `max`, whatever the length of `text`.
 */
export function sanitize(text: string, max = QUOTE_MAX, quoteMarks = false): string {
  const { shown, cut } = escapeUpTo(text, max, quoteMarks);
  return cut ? shown + '...' : shown;
}

function escapeUpTo(
  text: string,
  max: number,
  quoteMarks: boolean,
): { shown: string; cut: boolean } {
  let shown = '';
  let i = 0;
  while (i < text.length) {
    const code = text.codePointAt(i)!;
    const ch = String.fromCodePoint(code);
    let piece: string;
    if (quoteMarks && (ch === '"' || ch === '\\')) piece = '\\' + ch;
    else if (UNPRINTABLE.test(ch)) piece = escapeChar(ch);
    else piece = ch;
    if (shown.length + piece.length > max) return { shown, cut: true };
    shown += piece;
    i += ch.length;
  }
  return { shown, cut: false };
}

/**
 * A string from a file as a message quotes it: `"red"`, `"\u001b[2J"`, or for a long one
 * `"aaaa..." (100000 characters)`.
 */
export function quote(text: string, max = QUOTE_MAX): string {
  const { shown, cut } = escapeUpTo(text, max, true);
  return cut ? `"${shown}..." (${text.length} characters)` : `"${shown}"`;
}

/**
 * The last guard of a message writer: the message as one printable line (line breaks and
 * other unprintable characters escaped), at most `max` characters. Messages built with
 * `quote` already pass unchanged.
 */
export function printableLine(message: string, max = 2000): string {
  return sanitize(message, max, false);
}

/** `materials` + `red` → `materials.red`; keys that are not identifiers are quoted. */
export function childPath(base: string, key: string): string {
  if (key.length <= QUOTE_MAX && /^[A-Za-z_$][A-Za-z0-9_$]*$/.test(key)) {
    return base === '' ? key : `${base}.${key}`;
  }
  return `${base}[${quote(key)}]`;
}

export function indexPath(base: string, index: number): string {
  return `${base}[${index}]`;
}
