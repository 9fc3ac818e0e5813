/**
 * Small building blocks of the scene validator (load.ts). Each `expect*` helper checks one
 * value, records a problem naming its JSON path and the offending value when it fails, and
 * returns the checked value or `undefined`. They never throw: the loader collects every
 * problem in one pass and throws once, so a user can fix a file in one round trip.
 */

import { childPath, indexPath, quote } from '../../util/message.ts';
import type { Vec3 } from '../format/types.ts';

export { childPath, indexPath };
export { utf8Length } from '../../io/utf8.ts';

/** The problems found so far, each a complete sentence that starts with a JSON path. */
export type Problems = string[];

/**
 * A rule on a number: `ok` decides, `rule` completes "<path> must ...", e.g. "be > 0"; it
 * may depend on the value, to name the side of a range that was broken.
 */
export interface NumberRule {
  ok: (x: number) => boolean;
  rule: string | ((x: number) => string);
}

export const POSITIVE: NumberRule = { ok: (x) => x > 0, rule: 'be > 0' };
export const NON_NEGATIVE: NumberRule = { ok: (x) => x >= 0, rule: 'be >= 0' };
export const UNIT_INTERVAL: NumberRule = { ok: (x) => x >= 0 && x <= 1, rule: 'be in [0, 1]' };

/** Describes a value for "got ..." in a message: numbers and strings as written in JSON. */
export function describe(value: unknown): string {
  if (value === null) return 'null';
  if (value === undefined) return 'undefined';
  if (typeof value === 'number') return String(value);
  if (typeof value === 'string') return quote(value);
  if (typeof value === 'boolean') return String(value);
  if (Array.isArray(value)) {
    // Short arrays of numbers are shown in full; they are the usual vector mistakes.
    if (value.length <= 4 && value.every((x) => typeof x === 'number')) {
      return `[${value.join(', ')}]`;
    }
    return `an array of length ${value.length}`;
  }
  if (typeof value === 'object') return 'an object';
  return `a ${typeof value}`;
}

/**
 * A value of the wrong type, named by its type: `the string "0"` where a number or an
 * object is wanted (a quoted number reads like the number itself otherwise), `an object`,
 * `an array of length 2`. Never `[object Object]`: every type has words.
 */
export function describeType(value: unknown): string {
  return typeof value === 'string' ? `the string ${quote(value)}` : describe(value);
}

export function formatVec(v: Vec3): string {
  return `[${v[0]}, ${v[1]}, ${v[2]}]`;
}

/**
 * Levenshtein distance if it is at most `k`, else k + 1. Only the diagonal band of width
 * 2k + 1 is computed (Ukkonen 1985), so a comparison costs O(k · length), not O(length²).
 */
export function boundedEditDistance(a: string, b: string, k: number): number {
  if (Math.abs(a.length - b.length) > k) return k + 1;
  const far = k + 1;
  let previous = new Array<number>(b.length + 1);
  let current = new Array<number>(b.length + 1);
  for (let j = 0; j <= b.length; j++) previous[j] = j <= k ? j : far;
  for (let i = 1; i <= a.length; i++) {
    const lo = Math.max(1, i - k);
    const hi = Math.min(b.length, i + k);
    current.fill(far);
    current[0] = i <= k ? i : far;
    let rowMin = current[0];
    for (let j = lo; j <= hi; j++) {
      const substitution = previous[j - 1] + (a[i - 1] === b[j - 1] ? 0 : 1);
      const d = Math.min(previous[j] + 1, current[j - 1] + 1, substitution, far);
      current[j] = d;
      if (d < rowMin) rowMin = d;
    }
    if (rowMin > k) return far; // every path through this row already costs more than k
    [previous, current] = [current, previous];
  }
  return Math.min(previous[b.length], far);
}

/**
 * The candidate a misspelt `word` most likely meant, if any is close enough (at most 2
 * edits, fewer for short names). Each candidate costs O(length): see boundedEditDistance.
 */
export function closest(word: string, candidates: Iterable<string>): string | undefined {
  if (word.length > 64) return undefined; // not a typo
  let best: string | undefined;
  let bestDistance = Infinity;
  const lower = word.toLowerCase();
  for (const candidate of candidates) {
    if (Math.abs(candidate.length - word.length) > 2) continue; // too far apart to be a typo
    const allowed = Math.min(2, Math.floor(candidate.length / 3));
    const distance =
      candidate.toLowerCase() === lower ? 0 : boundedEditDistance(word, candidate, allowed);
    if (distance <= allowed && distance < bestDistance) {
      best = candidate;
      bestDistance = distance;
      if (distance === 0) break;
    }
  }
  return best;
}

/** A JSON object (not null, not an array), or a problem. */
export function expectObject(
  value: unknown,
  path: string,
  problems: Problems,
): Record<string, unknown> | undefined {
  if (typeof value === 'object' && value !== null && !Array.isArray(value)) {
    return value as Record<string, unknown>;
  }
  if (missing(value, path, problems, 'an object')) return undefined;
  problems.push(`${path} must be an object, got ${describeType(value)}`);
  return undefined;
}

/**
 * Unknown keys are errors at every level, so that a misspelt optional key (which would
 * otherwise silently take its default) cannot pass unnoticed. Missing required keys are
 * reported by the expect* helper that reads them (undefined counts as missing).
 */
export function expectKnownKeys(
  obj: Record<string, unknown>,
  path: string,
  known: readonly string[],
  problems: Problems,
): void {
  for (const key of Object.keys(obj)) {
    if (known.includes(key)) continue;
    const guess = closest(key, known);
    const hint = guess === undefined ? '' : ` (did you mean ${guess}?)`;
    problems.push(`${childPath(path, key)} is not a known key${hint}`);
  }
}

/** Records the problem of a missing value; true if `value` is missing. */
function missing(value: unknown, path: string, problems: Problems, what: string): boolean {
  if (value !== undefined) return false;
  problems.push(`${path} is required but missing (${what})`);
  return true;
}

/** One of a few fixed strings (a type tag or the format), or a problem. */
export function expectOneOf<T extends string>(
  value: unknown,
  path: string,
  options: readonly T[],
  problems: Problems,
): T | undefined {
  if (options.includes(value as T)) return value as T;
  const list = options.map((o) => JSON.stringify(o)).join(', ');
  const what = options.length === 1 ? list : `one of ${list}`;
  if (!missing(value, path, problems, what)) {
    problems.push(`${path} must be ${what}, got ${describe(value)}`);
  }
  return undefined;
}

/** Why a non-number failed: a quoted number gets a specific hint, it is a common mistake. */
function notANumber(value: unknown, path: string, what: string): string {
  const quoted =
    typeof value === 'string' && value.trim() !== '' && Number.isFinite(Number(value))
      ? ' (numbers must not be quoted)'
      : '';
  return `${path} must be ${what}, got ${describeType(value)}${quoted}`;
}

/** A finite number (NaN and ±Infinity can arrive through validateScene), or a problem. */
export function expectNumber(
  value: unknown,
  path: string,
  problems: Problems,
  rule?: NumberRule,
): number | undefined {
  if (typeof value !== 'number' || !Number.isFinite(value)) {
    if (missing(value, path, problems, 'a number')) return undefined;
    problems.push(notANumber(value, path, 'a finite number'));
    return undefined;
  }
  if (rule !== undefined && !rule.ok(value)) {
    const text = typeof rule.rule === 'string' ? rule.rule : rule.rule(value);
    problems.push(`${path} must ${text}, got ${describe(value)}`);
    return undefined;
  }
  return value;
}

/** An integer in [min, max]; the message states the whole rule, whatever part failed. */
export function expectInteger(
  value: unknown,
  path: string,
  problems: Problems,
  min: number,
  max: number,
): number | undefined {
  if (typeof value === 'number' && Number.isInteger(value) && value >= min && value <= max) {
    return value;
  }
  const what = max === Infinity ? `an integer >= ${min}` : `an integer in [${min}, ${max}]`;
  if (missing(value, path, problems, what)) return undefined;
  problems.push(notANumber(value, path, what));
  return undefined;
}

export function expectString(value: unknown, path: string, problems: Problems): string | undefined {
  if (typeof value === 'string') return value;
  if (missing(value, path, problems, 'a string')) return undefined;
  problems.push(`${path} must be a string, got ${describe(value)}`);
  return undefined;
}

/** Exactly three finite numbers, each obeying `rule` if given: a fresh copy, else undefined. */
export function plainVec3(value: unknown, rule?: NumberRule): Vec3 | undefined {
  if (!Array.isArray(value) || value.length !== 3) return undefined;
  const [x, y, z] = value as unknown[];
  if (
    typeof x === 'number' &&
    typeof y === 'number' &&
    typeof z === 'number' &&
    Number.isFinite(x) &&
    Number.isFinite(y) &&
    Number.isFinite(z) &&
    (rule === undefined || (rule.ok(x) && rule.ok(y) && rule.ok(z)))
  ) {
    return [x, y, z];
  }
  return undefined;
}

/** Exactly three finite numbers, each obeying `rule` if given; a fresh copy, or a problem. */
export function expectVec3(
  value: unknown,
  path: string,
  problems: Problems,
  rule?: NumberRule,
): Vec3 | undefined {
  // The common case without building the elements' paths (a scene of 10,000 spheres has
  // 10,000 centres); anything else goes the long way, which names each problem.
  const plain = plainVec3(value, rule);
  if (plain !== undefined) return plain;
  if (!Array.isArray(value) || value.length !== 3) {
    if (missing(value, path, problems, 'an array of 3 numbers')) return undefined;
    problems.push(`${path} must be an array of 3 numbers, got ${describeType(value)}`);
    return undefined;
  }
  const before = problems.length;
  const out = value.map((x, i) => expectNumber(x, indexPath(path, i), problems, rule));
  return problems.length === before ? (out as Vec3) : undefined;
}

export function sub(a: Vec3, b: Vec3): Vec3 {
  return [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
}

export function cross(a: Vec3, b: Vec3): Vec3 {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

/** Math.hypot avoids overflow and underflow of the squares for extreme coordinates. */
export function length(a: Vec3): number {
  return Math.hypot(a[0], a[1], a[2]);
}

/** The unit vector along `a`, or undefined if `a` is zero (or its length is not finite). */
export function normalize(a: Vec3): Vec3 | undefined {
  const len = length(a);
  if (len === 0 || !Number.isFinite(len)) return undefined;
  return [a[0] / len, a[1] / len, a[2] / len];
}
