/**
 * fast-check arbitraries that mutate valid inputs the way a fuzzer (or a careless script)
 * does: scenes at the level of JSON values (replace, delete, add, retype a node, with
 * numbers and strings chosen at the edges of every rule), then at the level of bytes
 * (flip, insert, delete, truncate, duplicate a key); argument lists by inserting,
 * deleting and replacing tokens drawn from the options and from hostile values.
 */
import fc from 'fast-check';
import { readFileSync, readdirSync } from 'node:fs';
import { join } from 'node:path';
import { ROOT } from '../helpers/render.ts';

/** The canonical scenes plus the corpus' small base scene: what gets mutated. */
export const SEED_SCENES: { name: string; value: unknown }[] = [
  ...readdirSync(join(ROOT, 'scenes'))
    .filter((f) => f.endsWith('.json'))
    .map((f) => ({ name: f, value: JSON.parse(readFileSync(join(ROOT, 'scenes', f), 'utf8')) })),
  {
    name: 'fuzz/valid-base.json',
    value: JSON.parse(readFileSync(join(ROOT, 'tests/fuzz/corpus/valid-base.json'), 'utf8')),
  },
];

/** Numbers at the edges of the format's rules and of double precision. */
const edgeNumber = fc.constantFrom(
  0,
  -0,
  -1,
  0.5,
  1,
  2,
  3,
  45,
  179.9999,
  180,
  1e-320,
  5e-324,
  1e-200,
  1e-160,
  1e12,
  1.0000001e12,
  1e38,
  3.5e38,
  1e200,
  1e308,
  -1e308,
  2 ** 31,
  2 ** 53 + 2,
  4097,
  16777217,
  1048576,
  1048577,
  64,
  65,
  100001,
);

const edgeString = fc.constantFrom(
  '',
  'white',
  'light',
  'red',
  'sphere',
  'quad',
  'diffuse',
  'conductor',
  'dielectric',
  'pathwise-scene/1',
  '__proto__',
  'constructor',
  'toString',
  '\u001b[2J',
  '\u0000',
  '\ud800',
  '\u202e',
  'k'.repeat(300),
);

const leaf: fc.Arbitrary<unknown> = fc.oneof(
  { weight: 4, arbitrary: edgeNumber },
  { weight: 2, arbitrary: fc.double({ noNaN: true }) },
  { weight: 2, arbitrary: edgeString },
  { weight: 1, arbitrary: fc.string({ unit: 'binary', maxLength: 12 }) },
  { weight: 1, arbitrary: fc.constantFrom(null, true, false) },
);

/** A hostile JSON value: a leaf, a vector of leaves, or a small nest of them. */
export const hostileValue: fc.Arbitrary<unknown> = fc.oneof(
  { weight: 5, arbitrary: leaf },
  { weight: 3, arbitrary: fc.array(edgeNumber, { minLength: 0, maxLength: 5 }) },
  { weight: 1, arbitrary: fc.array(leaf, { maxLength: 3 }) },
  { weight: 1, arbitrary: fc.dictionary(edgeString, leaf, { maxKeys: 3 }) },
);

type Op =
  | { kind: 'replace'; at: number; value: unknown }
  | { kind: 'delete'; at: number }
  | { kind: 'add'; at: number; key: string; value: unknown }
  | { kind: 'copy'; at: number; from: number };

const op: fc.Arbitrary<Op> = fc.oneof(
  {
    weight: 6,
    arbitrary: fc.record({
      kind: fc.constant('replace' as const),
      at: fc.nat(),
      value: hostileValue,
    }),
  },
  { weight: 2, arbitrary: fc.record({ kind: fc.constant('delete' as const), at: fc.nat() }) },
  {
    weight: 1,
    arbitrary: fc.record({
      kind: fc.constant('add' as const),
      at: fc.nat(),
      key: edgeString,
      value: hostileValue,
    }),
  },
  {
    weight: 1,
    arbitrary: fc.record({ kind: fc.constant('copy' as const), at: fc.nat(), from: fc.nat() }),
  },
);

/** Every (container, key) slot of a JSON value, depth first. */
function slots(root: unknown): { parent: any; key: string | number }[] {
  const out: { parent: any; key: string | number }[] = [];
  const walk = (v: unknown) => {
    if (Array.isArray(v)) {
      v.forEach((x, i) => {
        out.push({ parent: v, key: i });
        walk(x);
      });
    } else if (typeof v === 'object' && v !== null) {
      for (const k of Object.keys(v)) {
        out.push({ parent: v, key: k });
        walk((v as any)[k]);
      }
    }
  };
  walk(root);
  return out;
}

function applyOps(value: unknown, ops: Op[]): unknown {
  const root = structuredClone(value);
  for (const o of ops) {
    const all = slots(root);
    if (all.length === 0) break;
    const { parent, key } = all[o.at % all.length];
    if (o.kind === 'replace') parent[key] = structuredClone(o.value);
    else if (o.kind === 'delete') {
      if (Array.isArray(parent)) parent.splice(key as number, 1);
      else delete parent[key];
    } else if (o.kind === 'add') {
      const target = typeof parent[key] === 'object' && parent[key] !== null ? parent[key] : parent;
      if (Array.isArray(target)) target.push(structuredClone(o.value));
      else
        Object.defineProperty(target, o.key, {
          value: structuredClone(o.value),
          enumerable: true,
          writable: true,
          configurable: true,
        });
    } else {
      const source = all[o.from % all.length];
      parent[key] = structuredClone(source.parent[source.key]);
    }
  }
  return root;
}

type ByteOp =
  | { kind: 'flip'; at: number; byte: number }
  | { kind: 'insert'; at: number; bytes: number[] }
  | { kind: 'delete'; at: number; length: number }
  | { kind: 'truncate'; at: number }
  | { kind: 'duplicate-key'; at: number };

/** Bytes that matter to JSON and UTF-8 parsers. */
const interestingByte = fc.constantFrom(
  0x00,
  0x1b,
  0x22,
  0x2c,
  0x3a,
  0x5b,
  0x5d,
  0x7b,
  0x7d,
  0x5c,
  0x0a,
  0x80,
  0xbf,
  0xc0,
  0xc3,
  0xe2,
  0xed,
  0xef,
  0xf0,
  0xf4,
  0xfe,
  0xff,
);

const byteOp: fc.Arbitrary<ByteOp> = fc.oneof(
  {
    weight: 3,
    arbitrary: fc.record({
      kind: fc.constant('flip' as const),
      at: fc.nat(),
      byte: fc.oneof(interestingByte, fc.integer({ min: 0, max: 255 })),
    }),
  },
  {
    weight: 2,
    arbitrary: fc.record({
      kind: fc.constant('insert' as const),
      at: fc.nat(),
      bytes: fc.array(interestingByte, { minLength: 1, maxLength: 4 }),
    }),
  },
  {
    weight: 2,
    arbitrary: fc.record({
      kind: fc.constant('delete' as const),
      at: fc.nat(),
      length: fc.integer({ min: 1, max: 16 }),
    }),
  },
  { weight: 1, arbitrary: fc.record({ kind: fc.constant('truncate' as const), at: fc.nat() }) },
  {
    weight: 2,
    arbitrary: fc.record({ kind: fc.constant('duplicate-key' as const), at: fc.nat() }),
  },
);

function applyByteOps(bytes: Uint8Array, ops: ByteOp[]): Uint8Array {
  let b = Array.from(bytes);
  for (const o of ops) {
    const at = b.length === 0 ? 0 : o.at % (b.length + 1);
    if (o.kind === 'flip' && b.length > 0) b[o.at % b.length] = o.byte;
    else if (o.kind === 'insert') b.splice(at, 0, ...o.bytes);
    else if (o.kind === 'delete') b.splice(at, o.length);
    else if (o.kind === 'truncate') b = b.slice(0, at);
    else if (o.kind === 'duplicate-key') {
      // Repeat a `"key": value,` member right after itself: the same key twice.
      const text = Buffer.from(b).toString('latin1');
      const members = [...text.matchAll(/"[A-Za-z]+":\s*[^,{}\[\]]+,/g)];
      if (members.length > 0) {
        const m = members[o.at % members.length];
        const end = m.index! + m[0].length;
        b.splice(end, 0, ...Buffer.from(m[0], 'latin1'));
      }
    }
  }
  return Uint8Array.from(b);
}

export interface MutatedScene {
  seed: string;
  bytes: Uint8Array;
}

/**
 * A mutated scene file: a seed scene, 0 to 3 value-level mutations, serialized (compact
 * or indented), then 0 to 2 byte-level mutations (about half the cases keep valid JSON).
 */
export const mutatedScene: fc.Arbitrary<MutatedScene> = fc
  .record({
    seed: fc.nat({ max: SEED_SCENES.length - 1 }),
    ops: fc.array(op, { maxLength: 3 }),
    indent: fc.constantFrom(0, 2),
    bytes: fc.oneof(
      { weight: 1, arbitrary: fc.constant([] as ByteOp[]) },
      { weight: 1, arbitrary: fc.array(byteOp, { minLength: 1, maxLength: 2 }) },
    ),
  })
  .map(({ seed, ops, indent, bytes }) => {
    const value = applyOps(SEED_SCENES[seed].value, ops);
    const text = JSON.stringify(value, null, indent) ?? 'null';
    return {
      seed: SEED_SCENES[seed].name,
      bytes: applyByteOps(new TextEncoder().encode(text), bytes),
    };
  });

/** Option names and hostile option values for argument lists. */
const optionToken = fc.constantFrom(
  '--spp',
  '--width',
  '--height',
  '--bounces',
  '--seed',
  '--threads',
  '--exposure',
  '--estimator',
  '--sampler',
  '--stripe-rows',
  '--json',
  '--json=false',
  '--json=',
  '--out',
  '--spp=2',
  '--exposure=1.5',
  '--',
  '-',
  '--frobnicate',
  '--\u001b[2J',
);
const valueToken = fc.constantFrom(
  '0',
  '1',
  '2',
  '3',
  '-1',
  '0x10',
  '1e2',
  '1e-2',
  '',
  ' 1',
  '+1',
  '1.5',
  '.5',
  'NaN',
  'Infinity',
  '99999999999999999999',
  '33',
  'bsdf',
  'nee-mis',
  'sobol',
  'independent',
  'x.pfm',
  'x.png',
  'x.jpg',
  '\u0000',
);

export interface MutatedArgs {
  argv: string[];
}

/**
 * An argument list for `render` (without the word `render`): a valid base (the scene,
 * --out, small size) with 1 to 3 tokens (or option-value pairs) inserted, deleted or replaced;
 * with `pairsOnly`, only option-value pairs appended (the values stay hostile). Accepted sizes
 * stay small (numbers are at most 33, with the base scene's 12 x 10 pixels and 2 spp).
 */
export function mutatedArgs(
  scene: string,
  out: string,
  { pairsOnly = false } = {},
): fc.Arbitrary<string[]> {
  const base = [scene, '--out', out];
  // Well-formed pairs (an option that takes a value, and a value), or a switch alone.
  const pair = fc.oneof(
    fc
      .tuple(
        fc.constantFrom(
          '--spp',
          '--width',
          '--height',
          '--bounces',
          '--seed',
          '--threads',
          '--exposure',
          '--estimator',
          '--sampler',
          '--stripe-rows',
        ),
        valueToken,
      )
      .map(([option, value]): string[] => [option, value]),
    fc.constant(['--json']),
  );
  const edit = fc.record({
    kind: pairsOnly
      ? fc.constant('append')
      : fc.constantFrom('append', 'append', 'insert', 'delete', 'replace'),
    at: fc.nat(),
    token: fc.oneof(optionToken, valueToken, fc.string({ unit: 'binary', maxLength: 6 })),
    pair,
  });
  return fc.array(edit, { minLength: 1, maxLength: 3 }).map((edits) => {
    const argv = [...base];
    for (const e of edits) {
      const at = e.at % (argv.length + 1);
      if (e.kind === 'append') argv.push(...e.pair);
      else if (e.kind === 'insert') argv.splice(at, 0, e.token);
      else if (e.kind === 'delete' && argv.length > 0) argv.splice(at % argv.length, 1);
      else if (argv.length > 0) argv.splice(at % argv.length, 1, e.token);
    }
    return argv;
  });
}
