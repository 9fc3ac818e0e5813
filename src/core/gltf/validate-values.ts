/**
 * The value checks every part of the glTF validation uses: one JSON value at
 * a JSON path, checked for its JSON type first and its range second, so that
 * a value of the wrong type is named as such (`"scene": "0"` is "must be an
 * integer index, got the string \"0\"", not an index out of range). glTF 2.0
 * §5 ("Properties reference") gives each property's type; every index is a
 * `glTFid`, an integer ≥ 0 (§3.1 "Indices and names", schema glTFid.schema.json).
 */
import { quote } from '../util/message.ts';
import { GltfError } from './errors.ts';

export type Json = Record<string, unknown>;

/** Entries of one kind (nodes, meshes, accessors…) a file may have. */
export const MAX_OBJECTS = 1_000_000;

export function isObject(v: unknown): v is Json {
  return typeof v === 'object' && v !== null && !Array.isArray(v);
}

export function fail(path: string, what: string): never {
  throw new GltfError(`${path}: ${what}`);
}

/** A JSON value for a message: its JSON type, and the value itself where it is short. */
export function describeValue(v: unknown): string {
  if (v === undefined) return 'nothing';
  if (v === null) return 'null';
  if (typeof v === 'string') return `the string ${quote(v)}`;
  if (typeof v === 'number') return String(v);
  if (typeof v === 'boolean') return `the boolean ${String(v)}`;
  if (Array.isArray(v)) return `an array of ${v.length} element${v.length === 1 ? '' : 's'}`;
  if (typeof v === 'object') return 'an object';
  return `a ${typeof v}`;
}

/** The array at json[key] (absent: empty), each element an object. */
export function list(json: Json, key: string, path = key): Json[] {
  const v = json[key];
  if (v === undefined) return [];
  if (!Array.isArray(v)) fail(path, `must be an array, got ${describeValue(v)}`);
  if (v.length > MAX_OBJECTS) fail(path, `${v.length} entries, over the limit of ${MAX_OBJECTS}`);
  v.forEach((e, i) => {
    if (!isObject(e)) fail(`${path}[${i}]`, `must be an object, got ${describeValue(e)}`);
  });
  return v as Json[];
}

export function integer(
  o: Json,
  key: string,
  path: string,
  min: number,
  max = Number.MAX_SAFE_INTEGER,
): number | undefined {
  const v = o[key];
  if (v === undefined) return undefined;
  if (typeof v !== 'number' || !Number.isInteger(v) || v < min || v > max) {
    fail(`${path}.${key}`, `must be an integer in [${min}, ${max}], got ${describeValue(v)}`);
  }
  return v;
}

export function required(o: Json, key: string, path: string, min: number, max?: number): number {
  const v = integer(o, key, path, min, max);
  if (v === undefined) fail(`${path}.${key}`, 'is required');
  return v;
}

/**
 * An index `v` (found at `path`) into the file's array `what` of `n` entries: a wrong
 * JSON type is named as such, an integer out of range names the array's length.
 */
export function indexValue(v: unknown, path: string, n: number, what: string): number {
  if (typeof v !== 'number' || !Number.isInteger(v)) {
    fail(path, `must be an integer index into ${what}, got ${describeValue(v)}`);
  }
  if (v < 0 || v >= n) fail(path, `refers to ${what}[${v}], but the file has ${n}`);
  return v;
}

/** The optional index o[key] into `what` (n entries). */
export function index(
  o: Json,
  key: string,
  path: string,
  n: number,
  what: string,
): number | undefined {
  const v = o[key];
  if (v === undefined) return undefined;
  return indexValue(v, `${path}.${key}`, n, what);
}

/** The array of indices o[key] into `what` (n entries), absent: empty; duplicates refused. */
export function indexArray(
  o: Json,
  key: string,
  path: string,
  n: number,
  what: string,
  unique = true,
): number[] {
  const v = o[key];
  if (v === undefined) return [];
  if (!Array.isArray(v)) fail(`${path}.${key}`, `must be an array, got ${describeValue(v)}`);
  const seen = new Set<number>();
  v.forEach((x, k) => {
    const i = indexValue(x, `${path}.${key}[${k}]`, n, what);
    // glTF schemas declare these arrays "uniqueItems": true (glTF 2.0 §5).
    if (unique && seen.has(i)) fail(`${path}.${key}`, `lists ${what}[${i}] twice`);
    seen.add(i);
  });
  return v as number[];
}

export function finiteArray(o: Json, key: string, path: string, length: number): void {
  const v = o[key];
  if (v === undefined) return;
  if (
    !Array.isArray(v) ||
    v.length !== length ||
    !v.every((x) => typeof x === 'number' && Number.isFinite(x))
  ) {
    fail(`${path}.${key}`, `must be ${length} finite numbers`);
  }
}

/** A number at o[key], if present, finite and within [min, max]. */
export function bounded(o: unknown, key: string, path: string, min: number, max: number): void {
  if (!isObject(o) || o[key] === undefined) return;
  const v = o[key];
  if (typeof v !== 'number' || !(v >= min && v <= max)) {
    fail(`${path}.${key}`, `must be a number in [${min}, ${max}], got ${describeValue(v)}`);
  }
}

/** An array of `length` numbers at o[key], if present, each within [min, max]. */
export function boundedArray(
  o: unknown,
  key: string,
  path: string,
  length: number,
  min: number,
  max: number,
): void {
  if (!isObject(o) || o[key] === undefined) return;
  const v = o[key];
  if (
    !Array.isArray(v) ||
    v.length !== length ||
    !v.every((x) => typeof x === 'number' && x >= min && x <= max)
  ) {
    fail(`${path}.${key}`, `must be ${length} numbers in [${min}, ${max}]`);
  }
}

/** A number at o[key] greater than `min` (exclusive) and finite; `what` says why. */
export function positive(o: Json, key: string, path: string, min = 0): number | undefined {
  const v = o[key];
  if (v === undefined) return undefined;
  if (typeof v !== 'number' || !(v > min) || !Number.isFinite(v)) {
    fail(`${path}.${key}`, `must be a finite number greater than ${min}, got ${describeValue(v)}`);
  }
  return v;
}

/** One of the strings `allowed` at o[key], if present. */
export function oneOf(o: Json, key: string, path: string, allowed: readonly string[]): void {
  const v = o[key];
  if (v === undefined) return;
  if (typeof v !== 'string' || !allowed.includes(v)) {
    fail(
      `${path}.${key}`,
      `must be one of ${allowed.map((a) => `"${a}"`).join(', ')}, got ${describeValue(v)}`,
    );
  }
}
