/**
 * A strict JSON parser (RFC 8259) for untrusted files, used instead of JSON.parse because
 * the scene format's "Bad input" rules need what JSON.parse does not give:
 * - a syntax error names its line and column (V8 prints a source snippet over two lines);
 * - a key that appears twice in one object is an error naming its path (JSON.parse keeps
 *   the last one, so `"radius": -1, "radius": 1` passes silently);
 * - nesting is iterative and bounded, so `[[[[…` neither overflows the stack nor
 *   allocates millions of arrays.
 * Everything else matches JSON.parse: the same values, `__proto__` as an ordinary own key,
 * numbers as doubles (an overflowing literal such as 1e400 becomes Infinity, which the
 * validator then rejects by path). The input is text; bytes go through decodeUtf8 first.
 * A leading byte-order mark is not JSON: callers drop it (decodeUtf8 does).
 */

import { childPath, indexPath, quote } from '../util/message.ts';

/** Arrays and objects nested deeper than this are rejected; scenes need about 5 levels. */
export const MAX_JSON_DEPTH = 512;

export class JsonError extends Error {
  override name = 'JsonError';
  /** 'duplicate' for a key given twice in one object, 'syntax' for everything else. */
  readonly kind: 'syntax' | 'duplicate';
  /** Offset in the text (UTF-16 code units), 1-based line and column (in characters). */
  readonly offset: number;
  readonly line: number;
  readonly column: number;
  /** JSON path of the duplicate key (`shapes[3].radius`); '' for syntax errors. */
  readonly path: string;

  constructor(kind: 'syntax' | 'duplicate', text: string, offset: number, what: string, path = '') {
    const { line, column } = lineColumn(text, offset);
    super(
      kind === 'duplicate'
        ? `${path} appears twice in one object (line ${line}, column ${column})`
        : `line ${line}, column ${column}: ${what}`,
    );
    this.kind = kind;
    this.offset = offset;
    this.line = line;
    this.column = column;
    this.path = path;
  }
}

/** 1-based line and column of `offset`; CRLF, LF and a lone CR end a line. */
export function lineColumn(text: string, offset: number): { line: number; column: number } {
  let line = 1;
  let start = 0;
  const end = Math.min(offset, text.length);
  for (let i = 0; i < end; i++) {
    const c = text.charCodeAt(i);
    if (c === 0x0a || (c === 0x0d && text.charCodeAt(i + 1) !== 0x0a)) {
      line++;
      start = i + 1;
    }
  }
  // Columns count characters, so a character outside the BMP counts once.
  let column = 1;
  for (let i = start; i < end; i++) {
    const c = text.charCodeAt(i);
    if (!(c >= 0xdc00 && c <= 0xdfff && i > start && isHigh(text.charCodeAt(i - 1)))) column++;
  }
  return { line, column };
}

function isHigh(c: number): boolean {
  return c >= 0xd800 && c <= 0xdbff;
}

interface Frame {
  /** The container being filled. */
  array: unknown[] | null;
  object: Record<string, unknown> | null;
  /** The key whose value is being parsed (objects). */
  key: string;
}

const hasOwn = Object.prototype.hasOwnProperty;

/**
 * Parses JSON text. Throws JsonError.
 *
 * Valid text (the common case) takes V8's native JSON.parse, 5–8× faster than the parser
 * below on a 1 MB scene, cold, and without its garbage: a scan first bounds the nesting
 * (so JSON.parse never sees `[[[[…` past MAX_JSON_DEPTH) and counts the keys written in
 * the text; JSON.parse keeps one of each duplicate key, so its objects hold as many keys
 * as the text only if no object repeats one. Anything else (a syntax error, a duplicate,
 * too deep) goes through the parser below, which finds the problem and names its place.
 */
export function parseJson(text: string): unknown {
  const keys = scanKeys(text);
  if (keys >= 0) {
    let value: unknown;
    let parsed = false;
    try {
      value = JSON.parse(text);
      parsed = true;
    } catch {
      // A syntax error: the parser below says where and what.
    }
    if (parsed) {
      const written = typeof value === 'object' && value !== null ? countKeys(value) : 0;
      if (written === keys) return value;
    }
  }
  return parseJsonStrict(text);
}

/** The hand-written parser alone, for every text (parseJson uses it where JSON.parse cannot). */
export function parseJsonStrict(text: string): unknown {
  return new Parser(text).parse();
}

/**
 * The keys written in JSON text (the colons outside strings), or -1 where arrays and
 * objects nest deeper than MAX_JSON_DEPTH. Exact for valid JSON; for anything else
 * JSON.parse throws and the value does not matter.
 */
function scanKeys(text: string): number {
  const n = text.length;
  let keys = 0;
  let depth = 0;
  for (let i = 0; i < n; i++) {
    const c = text.charCodeAt(i);
    if (c === 0x22 /* " */) {
      for (i++; i < n; i++) {
        const d = text.charCodeAt(i);
        if (d === 0x22) break;
        if (d === 0x5c /* \ */) i++;
      }
    } else if (c === 0x3a /* : */) {
      keys++;
    } else if (c === 0x7b /* { */ || c === 0x5b /* [ */) {
      if (++depth > MAX_JSON_DEPTH) return -1;
    } else if (c === 0x7d /* } */ || c === 0x5d /* ] */) {
      depth--;
    }
  }
  return keys;
}

/**
 * Own keys of every object in a JSON value, an object or array nested at most
 * MAX_JSON_DEPTH deep (numbers and strings are tested inline: this runs cold, once).
 */
function countKeys(value: object): number {
  let n = 0;
  if (Array.isArray(value)) {
    for (let i = 0; i < value.length; i++) {
      const x: unknown = value[i];
      if (typeof x === 'object' && x !== null) n += countKeys(x);
    }
    return n;
  }
  const object = value as Record<string, unknown>;
  const keys = Object.keys(object);
  n += keys.length;
  for (let i = 0; i < keys.length; i++) {
    const x = object[keys[i]];
    if (typeof x === 'object' && x !== null) n += countKeys(x);
  }
  return n;
}

class Parser {
  private pos = 0;
  private readonly stack: Frame[] = [];

  constructor(private readonly text: string) {}

  parse(): unknown {
    const text = this.text;
    let value: unknown;
    for (;;) {
      // A value starts here.
      this.skipWhitespace();
      const c = text.charCodeAt(this.pos);
      if (c === 0x7b /* { */ || c === 0x5b /* [ */) {
        if (this.stack.length >= MAX_JSON_DEPTH) {
          this.fail(`arrays and objects are nested deeper than ${MAX_JSON_DEPTH} levels`);
        }
        this.pos++;
        this.skipWhitespace();
        if (c === 0x7b) {
          const object: Record<string, unknown> = {};
          if (text.charCodeAt(this.pos) === 0x7d /* } */) {
            this.pos++;
            value = object;
          } else {
            const frame: Frame = { array: null, object, key: '' };
            this.stack.push(frame);
            this.readKey(frame);
            continue;
          }
        } else if (text.charCodeAt(this.pos) === 0x5d /* ] */) {
          this.pos++;
          value = [];
        } else {
          this.stack.push({ array: [], object: null, key: '' });
          continue;
        }
      } else if (c === 0x22 /* " */) {
        value = this.readString();
      } else if (c === 0x2d /* - */ || (c >= 0x30 && c <= 0x39)) {
        value = this.readNumber();
      } else if (c === 0x74 /* t */) {
        value = this.readLiteral('true', true);
      } else if (c === 0x66 /* f */) {
        value = this.readLiteral('false', false);
      } else if (c === 0x6e /* n */) {
        value = this.readLiteral('null', null);
      } else {
        this.fail(`expected a value, got ${this.here()}`);
      }

      // The value is complete: store it in its container, and close containers as they end.
      for (;;) {
        const frame = this.stack[this.stack.length - 1];
        if (frame === undefined) {
          this.skipWhitespace();
          if (this.pos < text.length) {
            this.fail(`expected the end of the file after the JSON value, got ${this.here()}`);
          }
          return value;
        }
        this.skipWhitespace();
        const next = text.charCodeAt(this.pos);
        if (frame.object !== null) {
          setOwn(frame.object, frame.key, value);
          if (next === 0x2c /* , */) {
            this.pos++;
            this.skipWhitespace();
            this.readKey(frame);
            break;
          }
          if (next !== 0x7d /* } */) {
            this.fail(`expected ',' or '}' after an object member, got ${this.here()}`);
          }
          value = frame.object;
        } else {
          frame.array!.push(value);
          if (next === 0x2c /* , */) {
            this.pos++;
            break;
          }
          if (next !== 0x5d /* ] */) {
            this.fail(`expected ',' or ']' after an array element, got ${this.here()}`);
          }
          value = frame.array;
        }
        this.pos++;
        this.stack.pop();
      }
    }
  }

  /** Reads `"key" :` of an object member, rejecting a key the object already has. */
  private readKey(frame: Frame): void {
    const start = this.pos;
    if (this.text.charCodeAt(start) !== 0x22) {
      this.fail(`expected a key in double quotes, got ${this.here()}`);
    }
    const key = this.readString();
    if (hasOwn.call(frame.object, key)) {
      frame.key = key;
      throw new JsonError('duplicate', this.text, start, '', this.path());
    }
    frame.key = key;
    this.skipWhitespace();
    if (this.text.charCodeAt(this.pos) !== 0x3a /* : */) {
      this.fail(`expected ':' after the key ${quote(key)}, got ${this.here()}`);
    }
    this.pos++;
  }

  private readString(): string {
    const text = this.text;
    const open = this.pos;
    let i = open + 1;
    // Fast path: no escapes.
    for (;;) {
      const c = text.charCodeAt(i);
      if (c === 0x22) {
        this.pos = i + 1;
        return text.slice(open + 1, i);
      }
      if (c === 0x5c || c < 0x20 || i >= text.length) break;
      i++;
    }
    let out = text.slice(open + 1, i);
    for (;;) {
      if (i >= text.length) {
        this.pos = open;
        this.fail('a string is not closed before the end of the file');
      }
      const c = text.charCodeAt(i);
      if (c === 0x22) {
        this.pos = i + 1;
        return out;
      }
      if (c < 0x20) {
        this.pos = i;
        this.fail(`control character ${quote(text[i])} must be escaped inside a string`);
      }
      if (c !== 0x5c) {
        const run = i;
        while (i < text.length) {
          const d = text.charCodeAt(i);
          if (d === 0x22 || d === 0x5c || d < 0x20) break;
          i++;
        }
        out += text.slice(run, i);
        continue;
      }
      const e = text[i + 1];
      const simple = ESCAPES[e];
      if (simple !== undefined) {
        out += simple;
        i += 2;
      } else if (e === 'u' && /^[0-9A-Fa-f]{4}$/.test(text.slice(i + 2, i + 6))) {
        out += String.fromCharCode(parseInt(text.slice(i + 2, i + 6), 16));
        i += 6;
      } else {
        this.pos = i;
        this.fail(
          `invalid escape ${quote(text.slice(i, i + 6))} in a string ` +
            '(allowed: \\" \\\\ \\/ \\b \\f \\n \\r \\t \\uXXXX)',
        );
      }
    }
  }

  private readNumber(): number {
    const text = this.text;
    const start = this.pos;
    let i = start;
    if (text.charCodeAt(i) === 0x2d) i++;
    const first = text.charCodeAt(i);
    if (first === 0x30) {
      i++;
      if (isDigit(text.charCodeAt(i))) {
        this.pos = start;
        this.fail('a number must not have leading zeros');
      }
    } else if (first >= 0x31 && first <= 0x39) {
      while (isDigit(text.charCodeAt(i))) i++;
    } else {
      this.pos = i;
      this.fail(`expected a digit in a number, got ${this.here()}`);
    }
    if (text.charCodeAt(i) === 0x2e /* . */) {
      i++;
      if (!isDigit(text.charCodeAt(i))) {
        this.pos = i;
        this.fail(`expected a digit after the decimal point, got ${this.here()}`);
      }
      while (isDigit(text.charCodeAt(i))) i++;
    }
    const e = text.charCodeAt(i);
    if (e === 0x65 || e === 0x45) {
      i++;
      const sign = text.charCodeAt(i);
      if (sign === 0x2b || sign === 0x2d) i++;
      if (!isDigit(text.charCodeAt(i))) {
        this.pos = i;
        this.fail(`expected a digit in the exponent, got ${this.here()}`);
      }
      while (isDigit(text.charCodeAt(i))) i++;
    }
    this.pos = i;
    return Number(text.slice(start, i));
  }

  private readLiteral<T>(word: string, value: T): T {
    if (this.text.startsWith(word, this.pos)) {
      this.pos += word.length;
      return value;
    }
    this.fail(`expected a value, got ${this.here()}`);
  }

  private skipWhitespace(): void {
    const text = this.text;
    let i = this.pos;
    for (;;) {
      const c = text.charCodeAt(i);
      if (c === 0x20 || c === 0x0a || c === 0x0d || c === 0x09) i++;
      else break;
    }
    this.pos = i;
  }

  /** The text at the current position, as a message shows it. */
  private here(): string {
    if (this.pos >= this.text.length) return 'the end of the file';
    const cp = this.text.codePointAt(this.pos)!;
    return quote(String.fromCodePoint(cp));
  }

  /** JSON path of the member or element being parsed. */
  private path(): string {
    let path = '';
    for (const frame of this.stack) {
      path =
        frame.object !== null ? childPath(path, frame.key) : indexPath(path, frame.array!.length);
    }
    return path;
  }

  private fail(what: string): never {
    throw new JsonError('syntax', this.text, this.pos, what);
  }
}

const ESCAPES: Record<string, string> = {
  '"': '"',
  '\\': '\\',
  '/': '/',
  b: '\b',
  f: '\f',
  n: '\n',
  r: '\r',
  t: '\t',
};

function isDigit(c: number): boolean {
  return c >= 0x30 && c <= 0x39;
}

/** obj[key] = value, as JSON.parse does it: `__proto__` becomes an own key. */
function setOwn(obj: Record<string, unknown>, key: string, value: unknown): void {
  if (key === '__proto__') {
    Object.defineProperty(obj, key, {
      value,
      writable: true,
      enumerable: true,
      configurable: true,
    });
  } else {
    obj[key] = value;
  }
}
