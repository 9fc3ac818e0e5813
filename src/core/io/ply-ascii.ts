/**
 * The body of an ASCII PLY file: one line per instance of an element, holding exactly
 * the values its properties declare, in order, a list as its count then that many items
 * (Turk 1994, "the ASCII format ... each element on its own line"; Bourke's PLY
 * description). Read line by line, not token by token: a face line with one index more
 * than its count would otherwise shift every value after it into the next instance,
 * and the rest of the mesh would be read wrong without a word. Blank lines between
 * instances are skipped; anything after the last instance is an error.
 */
import { FormatError } from './format-error.ts';
import { FLOAT32, type Element, type Reader } from './ply-header.ts';
import { isBlank, parseDecimal, quoteBytes } from './text-bytes.ts';

const NEWLINE = 10;

export class AsciiBody implements Reader {
  private pos: number;
  private line: number;
  private readonly firstLine: number;
  /** Values read on the current line, for messages. */
  private values = 0;

  constructor(
    private readonly bytes: Uint8Array,
    private readonly start: number,
  ) {
    this.pos = start;
    // The body starts on the line after end_header.
    let lines = 1;
    for (let i = 0; i < start; i++) if (bytes[i] === NEWLINE) lines++;
    this.firstLine = lines;
    this.line = lines;
  }

  rewind(): void {
    this.pos = this.start;
    this.line = this.firstLine;
  }

  where(): string {
    return ` (line ${this.line})`;
  }

  /** Skips blank lines and leading blanks: the instance's line is the next non-blank one. */
  begin(element: Element, index: number): void {
    const b = this.bytes;
    let i = this.pos;
    while (i < b.length && (isBlank(b[i]) || b[i] === NEWLINE)) {
      if (b[i] === NEWLINE) this.line++;
      i++;
    }
    if (i >= b.length) {
      throw new FormatError(
        'PLY',
        `the file ends in ${element.name} ${index} of the ${element.count} the header declares`,
      );
    }
    this.pos = i;
    this.values = 0;
  }

  /** The rest of the line must be blank. */
  end(element: Element, index: number): void {
    const b = this.bytes;
    let i = this.pos;
    while (i < b.length && isBlank(b[i])) i++;
    if (i < b.length && b[i] !== NEWLINE) {
      let e = i;
      while (e < b.length && !isBlank(b[e]) && b[e] !== NEWLINE) e++;
      throw new FormatError(
        'PLY',
        `${element.name} ${index}${this.where()}: the line holds more than the ${this.values} ` +
          `values its properties declare (list counts included), starting at ${quoteBytes(b, i, e)}`,
      );
    }
    this.pos = i;
  }

  finish(): void {
    const b = this.bytes;
    let i = this.pos;
    while (i < b.length && (isBlank(b[i]) || b[i] === NEWLINE)) {
      if (b[i] === NEWLINE) this.line++;
      i++;
    }
    if (i < b.length) {
      let e = i;
      while (e < b.length && !isBlank(b[e]) && b[e] !== NEWLINE) e++;
      throw new FormatError(
        'PLY',
        `line ${this.line}: more data after the last element the header declares, ` +
          `starting at ${quoteBytes(b, i, e)}`,
      );
    }
  }

  value(type: number, element: Element, index: number): number {
    const b = this.bytes;
    let i = this.pos;
    while (i < b.length && isBlank(b[i])) i++;
    // The last line cut short, with only blanks after it, is a file that ends early.
    let rest = i;
    while (rest < b.length && (isBlank(b[rest]) || b[rest] === NEWLINE)) rest++;
    if (rest >= b.length) {
      throw new FormatError(
        'PLY',
        `the file ends in ${element.name} ${index} of the ${element.count} the header declares`,
      );
    }
    if (b[i] === NEWLINE) {
      throw new FormatError(
        'PLY',
        `${element.name} ${index}${this.where()}: the line ends after ${this.values} values, ` +
          'fewer than its properties declare (list counts included)',
      );
    }
    let e = i;
    while (e < b.length && !isBlank(b[e]) && b[e] !== NEWLINE) e++;
    this.pos = e;
    this.values++;
    const x = parseDecimal(b, i, e);
    if (Number.isNaN(x) || (type < FLOAT32 && !Number.isInteger(x))) {
      throw new FormatError(
        'PLY',
        `${element.name} ${index}${this.where()}: expected ${type < FLOAT32 ? 'an integer' : 'a number'}, ` +
          `got ${quoteBytes(b, i, e)}`,
      );
    }
    return x;
  }
}
