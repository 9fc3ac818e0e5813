/**
 * Mutations that know nothing of a format (blind byte changes) and those that know only
 * JSON (a hostile value at a random path), shared by the generators.
 */
import type { Rng } from './rng.ts';

const INTERESTING = [0x00, 0x01, 0x7f, 0x80, 0xff, 0x20, 0x0a, 0x2d, 0x39];

/** One to four blind changes: bit flips, byte sets, cuts, duplicated or deleted ranges. */
export function blindMutate(bytes: Uint8Array, rng: Rng): { bytes: Uint8Array; name: string } {
  let b = bytes.slice();
  const names: string[] = [];
  const rounds = rng.range(1, 4);
  for (let r = 0; r < rounds && b.length > 0; r++) {
    const at = rng.int(b.length);
    switch (rng.int(7)) {
      case 0: {
        b[at] ^= 1 << rng.int(8);
        names.push(`flip@${at}`);
        break;
      }
      case 1: {
        b[at] = rng.pick(INTERESTING);
        names.push(`set@${at}`);
        break;
      }
      case 2: {
        b = b.slice(0, at);
        names.push(`cut@${at}`);
        break;
      }
      case 3: {
        const len = Math.min(rng.range(1, 64), b.length - at);
        const copy = b.slice(at, at + len);
        const to = rng.int(b.length);
        b = new Uint8Array([...b.subarray(0, to), ...copy, ...b.subarray(to)]);
        names.push(`dup${len}@${at}->${to}`);
        break;
      }
      case 4: {
        const len = Math.min(rng.range(1, 32), b.length - at);
        b = new Uint8Array([...b.subarray(0, at), ...b.subarray(at + len)]);
        names.push(`del${len}@${at}`);
        break;
      }
      case 5: {
        for (let i = 0; i < 4 && at + i < b.length; i++) b[at + i] = rng.int(256);
        names.push(`rand4@${at}`);
        break;
      }
      default: {
        // Many flips at once: a damaged transfer rather than one bad bit.
        for (let i = 0; i < 16; i++) b[rng.int(b.length)] ^= 1 << rng.int(8);
        names.push('flip16');
      }
    }
  }
  return { bytes: b, name: `blind:${names.join(',')}` };
}

/** Values a careless or hostile writer puts where a number, index or object belongs. */
export const HOSTILE_VALUES: readonly unknown[] = [
  -1,
  0,
  0.5,
  1e308,
  -1e308,
  1e-320,
  2 ** 31,
  2 ** 53,
  4294967296,
  '0',
  '',
  null,
  true,
  [],
  [0],
  {},
  'x'.repeat(300),
  [1e308, 1e308, 1e308],
];

type JsonPath = (string | number)[];

/** Every path into a JSON value (objects' keys and arrays' indices), the root excluded. */
export function jsonPaths(v: unknown, prefix: JsonPath = [], out: JsonPath[] = []): JsonPath[] {
  if (Array.isArray(v)) {
    v.forEach((x, i) => {
      out.push([...prefix, i]);
      jsonPaths(x, [...prefix, i], out);
    });
  } else if (v !== null && typeof v === 'object') {
    for (const [k, x] of Object.entries(v)) {
      out.push([...prefix, k]);
      jsonPaths(x, [...prefix, k], out);
    }
  }
  return out;
}

function parentOf(root: unknown, path: JsonPath): Record<string | number, unknown> {
  let v = root as Record<string | number, unknown>;
  for (const k of path.slice(0, -1)) v = v[k] as Record<string | number, unknown>;
  return v;
}

/** A deep copy with one value replaced, deleted or given a hostile sibling. */
export function mutateJson(root: unknown, rng: Rng): { json: unknown; name: string } {
  const copy = structuredClone(root);
  const paths = jsonPaths(copy);
  const path = rng.pick(paths);
  const parent = parentOf(copy, path);
  const key = path[path.length - 1];
  const where = path.join('.');
  const op = rng.int(10);
  if (op === 0 && !Array.isArray(parent)) {
    delete parent[key];
    return { json: copy, name: `json:delete ${where}` };
  }
  if (op === 1 && typeof parent[key] === 'number') {
    const n = parent[key] as number;
    const v = rng.pick([n * 1e300, -n, n + 1, n - 1, n * 1000, Math.floor(n / 2)]);
    parent[key] = Number.isFinite(v) ? v : 1e308;
    return { json: copy, name: `json:${where}=${parent[key]}` };
  }
  if (op === 2 && Array.isArray(parent[key])) {
    const arr = parent[key] as unknown[];
    if (arr.length > 0) arr.push(structuredClone(arr[rng.int(arr.length)]));
    else arr.push(0);
    return { json: copy, name: `json:grow ${where}` };
  }
  if (op === 3 && Array.isArray(parent[key])) {
    (parent[key] as unknown[]).length = rng.int((parent[key] as unknown[]).length);
    return { json: copy, name: `json:shrink ${where}` };
  }
  const v = rng.pick(HOSTILE_VALUES);
  parent[key] = structuredClone(v);
  return { json: copy, name: `json:${where}=${JSON.stringify(v).slice(0, 24)}` };
}
