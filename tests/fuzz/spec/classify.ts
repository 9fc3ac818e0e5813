/**
 * How a finished run is judged (issue 27, deliverable 6): a finite image, one clear line,
 * or notes for something honestly ignored; everything else is a failure with a name.
 */
export const GOOD = ['image', 'error', 'note'] as const;
export const FAILURES = [
  'crash',
  'signal',
  'timeout',
  'memory',
  'slow',
  'heavy',
  'multi-line',
  'internals',
  'unprintable',
  'silent-empty',
  'non-finite',
  'no-image',
  'accepted-invalid',
  'misleading',
] as const;
export type Outcome = (typeof GOOD)[number] | (typeof FAILURES)[number];

export function isFailure(o: Outcome): boolean {
  return !(GOOD as readonly string[]).includes(o);
}

/** What a user must never read: JavaScript's own words, or a stack. */
export const INTERNALS =
  /Cannot (read|set) propert|\[object Object\]|DataView|\bundefined\b|is not a function|is not iterable|RangeError|TypeError|ReferenceError|SyntaxError: Unexpected|Offset is outside|Invalid array length|Array buffer allocation|Maximum call stack|^\s+at .+:\d+/m;

const PRINTABLE = /^[^\p{Cc}\p{Cf}\p{Zl}\p{Zp}\p{Co}\p{Cs}]*$/u;

export interface RunFacts {
  status: number | null;
  signal: string | null;
  killed: 'timeout' | 'memory' | null;
  stderr: string;
  /** The PFM written, if any. */
  image: Float32Array | null;
  /** The case guarantees light in view (see Sample.lit). */
  lit: boolean;
  /** The case breaks a rule of its specification outright (see Mutation.invalid). */
  invalid: boolean;
  /** What its error line must match, if anything (see Mutation.expect). */
  expect?: string;
}

/** The outcome, and a short reason for a failure. */
export function classify(f: RunFacts): { outcome: Outcome; why: string } {
  if (f.killed) return { outcome: f.killed, why: `killed by the harness (${f.killed})` };
  if (f.signal) return { outcome: 'signal', why: `ended by ${f.signal}` };
  const lines = f.stderr.endsWith('\n') ? f.stderr.slice(0, -1).split('\n') : f.stderr.split('\n');
  const said = f.stderr === '' ? [] : lines;
  if (INTERNALS.test(f.stderr)) return { outcome: 'internals', why: firstLine(f.stderr) };
  if (said.some((l) => !PRINTABLE.test(l) || !l.startsWith('pathwise: '))) {
    return { outcome: 'unprintable', why: firstLine(f.stderr) };
  }
  if (f.status === 2) {
    if (said.length !== 1) return { outcome: 'multi-line', why: `${said.length} lines` };
    if (f.expect && !new RegExp(f.expect, 'i').test(said[0])) {
      return { outcome: 'misleading', why: `${said[0].slice(0, 200)} (expected /${f.expect}/)` };
    }
    return { outcome: 'error', why: '' };
  }
  if (f.status !== 0) return { outcome: 'crash', why: `exit ${f.status}: ${firstLine(f.stderr)}` };
  if (!f.image) return { outcome: 'no-image', why: 'exit 0 without a readable PFM' };
  if (!f.image.every(Number.isFinite)) return { outcome: 'non-finite', why: 'NaN/Inf in the PFM' };
  const dropped = /not finite|left out/.test(f.stderr);
  if (f.image.every((v) => v === 0) && (f.lit || dropped)) {
    return { outcome: 'silent-empty', why: firstLine(f.stderr) || 'all-zero image, no message' };
  }
  // Exit 0 for a file its specification forbids: a note that something was ignored is not
  // enough (a bad index in an ignored animation still means a corrupt file, issue 27 item 7).
  if (f.invalid)
    return { outcome: 'accepted-invalid', why: firstLine(f.stderr) || 'exit 0, no message' };
  // Something honestly ignored must be said: the note it needs (Mutation.expect).
  if (f.expect && !said.some((l) => new RegExp(f.expect!, 'i').test(l)))
    return { outcome: 'accepted-invalid', why: `exit 0 without a note matching /${f.expect}/` };
  return { outcome: said.length > 0 ? 'note' : 'image', why: '' };
}

function firstLine(s: string): string {
  return s.split('\n')[0].slice(0, 240);
}

/** A PFM reader of our own (the CLI's output is always `PF`, little-endian): rgb floats. */
export function readPfm(b: Uint8Array): Float32Array | null {
  let at = 0;
  const fields: string[] = [];
  while (fields.length < 4 && at < b.length && at < 200) {
    let s = '';
    while (at < b.length && /\s/.test(String.fromCharCode(b[at]))) at++;
    while (at < b.length && !/\s/.test(String.fromCharCode(b[at])))
      s += String.fromCharCode(b[at++]);
    fields.push(s);
  }
  at++; // the one whitespace byte after the scale
  const [tag, w, h, scale] = fields;
  const n = Number(w) * Number(h) * (tag === 'PF' ? 3 : 1);
  if ((tag !== 'PF' && tag !== 'Pf') || !Number.isInteger(n) || b.length - at !== n * 4)
    return null;
  const view = new DataView(b.buffer, b.byteOffset + at, n * 4);
  const le = Number(scale) < 0;
  const out = new Float32Array(n);
  for (let i = 0; i < n; i++) out[i] = view.getFloat32(i * 4, le);
  return out;
}
